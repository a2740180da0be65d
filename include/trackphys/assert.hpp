#pragma once

#include "trackphys/export.hpp"

/// Cheap internal consistency checks, on without NDEBUG (Debug builds) and whenever
/// TRACKPHYS_ENABLE_ASSERT is defined (the sanitizer builds define it). A failed check calls
/// the assert handler, which prints and aborts by default; tests install their own to see
/// that checks fire.
/// Bad user input is never an assert: it is a trackphys::Error with a message.

namespace trackphys {

/// Called on a failed TP_ASSERT with the condition text, message, file and line.
using AssertHandler = void (*)(const char* condition, const char* message, const char* file,
                               int line);

/// Replaces the handler; returns the previous one. Passing nullptr restores the default.
TRACKPHYS_API AssertHandler set_assert_handler(AssertHandler handler) noexcept;

namespace detail {
TRACKPHYS_API void assert_failed(const char* condition, const char* message, const char* file,
                                 int line);
}  // namespace detail

}  // namespace trackphys

#if !defined(NDEBUG) || defined(TRACKPHYS_ENABLE_ASSERT)
#define TP_ASSERT(condition, message)                                                    \
    do {                                                                                 \
        if (!(condition))                                                                \
            ::trackphys::detail::assert_failed(#condition, message, __FILE__, __LINE__); \
    } while (false)
#else
#define TP_ASSERT(condition, message) static_cast<void>(0)
#endif
