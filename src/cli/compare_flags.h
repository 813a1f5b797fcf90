#pragma once
// compare's command line: every flag read and checked before anything is rendered, so that a bad
// value is one line naming the flag and the fix, and no output folder is touched for it.
#include <optional>
#include <string>
#include <vector>

#include "compare_options.h"

namespace gbl::compare {

// The options of `gbufferlab compare ARGS`; unset when --help was asked (the help is printed).
// Throws UserError for anything the user must fix.
std::optional<CompareOptions> parseCompareOptions(const std::vector<std::string>& args);

}  // namespace gbl::compare
