#include "error.h"

namespace gbl {

std::string formatPlace(const std::string& file, int line, int column) {
    std::string place = file;
    if (line > 0) {
        place += ":" + std::to_string(line);
        if (column > 0) place += ":" + std::to_string(column);
    }
    return place;
}

void throwUserError(const std::string& message) { throw UserError(message); }

}  // namespace gbl
