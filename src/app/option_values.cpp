#include "option_values.h"

#include <cmath>
#include <limits>

#include "error.h"

namespace gbl {

std::string positiveFloatProblem(double v) {
    if (std::isnan(v) || !(v > 0.0)) return "expected a positive number, e.g. 1.5";
    if (v > double(std::numeric_limits<float>::max()))
        return "too large; the largest value a float holds is about 3.4e38";
    if (v < double(std::numeric_limits<float>::min()))
        return "too small; the smallest value a float holds at full precision is about 1.2e-38";
    return "";
}

std::vector<std::string> splitFlagList(const std::string& text, const std::string& flag) {
    std::vector<std::string> items;
    size_t start = 0;
    for (;;) {
        const size_t comma = text.find(',', start);
        items.push_back(text.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
        if (items.back().empty())
            throwUserError(flag + " " + quoteName(text) +
                           ": an empty name in the list; give names separated by single commas, e.g. ue4,ryse");
        if (comma == std::string::npos) break;
        start = comma + 1;
    }
    return items;
}

}  // namespace gbl
