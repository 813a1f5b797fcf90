#include "user_error.h"

#include <gtest/gtest.h>

#include "error.h"

namespace gbl::test {

std::string userErrorOf(const std::function<void()>& fn) {
    try {
        fn();
    } catch (const UserError& e) {
        return e.what();
    }
    ADD_FAILURE() << "no UserError";
    return "";
}

}  // namespace gbl::test
