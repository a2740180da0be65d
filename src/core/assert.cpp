#include "trackphys/assert.hpp"

#include <cstdio>
#include <cstdlib>

namespace trackphys {
namespace {

void default_assert_handler(const char* condition, const char* message, const char* file,
                            int line) {
    std::fprintf(stderr, "%s:%d: trackphys assertion failed: %s (%s)\n", file, line, condition,
                 message);
    std::abort();
}

AssertHandler current_handler = &default_assert_handler;

}  // namespace

AssertHandler set_assert_handler(AssertHandler handler) noexcept {
    AssertHandler previous = current_handler;
    current_handler = handler ? handler : &default_assert_handler;
    return previous;
}

namespace detail {
void assert_failed(const char* condition, const char* message, const char* file, int line) {
    current_handler(condition, message, file, line);
}
}  // namespace detail

}  // namespace trackphys
