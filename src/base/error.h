#pragma once
// Error policy (after Falcor's): asserts for our own bugs; a UserError for anything the user
// can fix (a file, a flag, a missing driver). A UserError's message is one line that names the
// file or flag, the place, what is wrong and the fix; main() prints it and exits non-zero.
#include <stdexcept>
#include <string>

namespace gbl {

struct UserError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// Builds "file: message" (or "file:line:col: message" when line > 0).
std::string formatPlace(const std::string& file, int line = 0, int column = 0);

[[noreturn]] void throwUserError(const std::string& message);

}  // namespace gbl
