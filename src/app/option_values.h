#pragma once
// Values of options the library checks as the command line does, with the flag named in the
// message: a comma-separated list (compare's --layouts, --ibl), a positive float (a suite's
// exposure, as --exposure).
#include <string>
#include <vector>

namespace gbl {

// The range parsePositiveFloatFlag accepts (a positive number a float holds at full precision,
// about 1.2e-38 to 3.4e38), for values read elsewhere (a suite's `exposure`): "" when `v` is in it,
// else why not ("not positive", "too small; ...", "too large; ...").
std::string positiveFloatProblem(double v);

// "a,b,c" -> {a, b, c}; an empty list or an empty item ("", ",", "a,,b", "a,") is a UserError
// naming the flag.
std::vector<std::string> splitFlagList(const std::string& text, const std::string& flag);

}  // namespace gbl
