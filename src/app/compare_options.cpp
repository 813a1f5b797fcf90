// What a comparison is asked to do (compare_options.h): the layouts it names, loaded and checked.
#include "compare_options.h"

#include <algorithm>
#include <filesystem>

#include "error.h"
#include "layout_catalog.h"
#include "option_values.h"

namespace gbl::compare {

bool CompareOptions::compareLighting() const {
    return modes.size() > 1 && std::find(modeNames.begin(), modeNames.end(), kGroundTruth) != modeNames.end();
}

std::string joinList(const std::vector<std::string>& items) {
    std::string out;
    for (const auto& s : items) out += (out.empty() ? "" : ", ") + s;
    return out;
}

// A run's files go to runs/<layout name>/<mode>/ and its row is named by the layout: two layouts
// of one name (the same file given twice, or two files whose `name` agrees) would overwrite each
// other's files and leave two rows that cannot be told apart, so they are refused before rendering.
void requireDistinctRunNames(const std::vector<Layout>& layouts) {
    for (size_t i = 0; i < layouts.size(); ++i)
        for (size_t k = 0; k < i; ++k) {
            if (layouts[k].name != layouts[i].name) continue;
            std::error_code ec;
            const std::string a = layouts[k].sourceFile, b = layouts[i].sourceFile;
            if (a == b || std::filesystem::equivalent(a, b, ec))
                throwUserError("--layouts: the layout " + quoteName(layouts[i].name) + " (" + escapeText(a) +
                               ") is given twice; give each layout once");
            throwUserError("--layouts: " + escapeText(a) + " and " + escapeText(b) + " are both named " +
                           quoteName(layouts[i].name) + ", so their runs would share runs/" +
                           escapeText(layouts[i].name) + "/; give one of them another name (its `name` key)");
        }
}

// "all" (or no flag) = every file in layouts/ but the reference; otherwise names or paths. Every
// file is parsed and validated here, before any rendering.
std::vector<Layout> resolveLayouts(const std::optional<std::string>& spec) {
    std::vector<std::string> names;
    const std::vector<std::string> known = listLayoutNames();
    const std::vector<std::string> given = spec ? splitFlagList(*spec, "--layouts") : std::vector<std::string>{"all"};
    if (given.size() > 1 && std::find(given.begin(), given.end(), "all") != given.end())
        throwUserError("--layouts " + quoteName(*spec) + ": 'all' already names every layout; give all alone, or names");
    if (given.front() == "all") {
        for (const auto& n : known)
            if (n != kReferenceLayout) names.push_back(n);
    } else {
        names = given;
    }
    std::vector<Layout> layouts;
    for (const std::string& n : names) {
        const bool isPath = n.find('/') != std::string::npos || n.find(".toml") != std::string::npos;
        if (!isPath && std::find(known.begin(), known.end(), n) == known.end())
            throwUserError("--layouts: unknown layout " + quoteName(n) + " (known: " + joinList(known) + ", or all)");
        layouts.push_back(loadLayout(n));
    }
    requireDistinctRunNames(layouts);
    return layouts;
}

}  // namespace gbl::compare
