#include "trackphys/assert.hpp"

#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

namespace trackphys {
namespace {

struct AssertFired : std::runtime_error {
    using std::runtime_error::runtime_error;
};

[[noreturn]] void throwing_handler(const char* condition, const char* message, const char*, int) {
    throw AssertFired(std::string(condition) + ": " + message);
}

int checked_divide(int a, int b) {
    TP_ASSERT(b != 0, "divisor must not be zero");
    return a / b;
}

TEST(Assert, ReplaceableHandlerSeesTheFailedCheck) {
    const AssertHandler previous = set_assert_handler(&throwing_handler);
    EXPECT_EQ(checked_divide(6, 3), 2);
#if !defined(NDEBUG) || defined(TRACKPHYS_ENABLE_ASSERT)
    try {
        checked_divide(1, 0);
        ADD_FAILURE() << "the assert did not fire";
    } catch (const AssertFired& fired) {
        EXPECT_EQ(std::string(fired.what()), "b != 0: divisor must not be zero");
    }
#endif
    set_assert_handler(previous);
}

}  // namespace
}  // namespace trackphys
