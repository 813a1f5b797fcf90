#pragma once
// The one-line message of the UserError that `fn` throws (a failure of the test, and "", when it
// throws none).
#include <functional>
#include <string>

namespace gbl::test {

std::string userErrorOf(const std::function<void()>& fn);

}  // namespace gbl::test
