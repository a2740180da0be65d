#pragma once

// Whether this build runs under AddressSanitizer (the asan preset), which runs the tests
// about ten times slower: tests that repeat one check over many random cases take fewer
// of them there, and the Release run keeps the full count.

namespace trackphys::test {

#if defined(__SANITIZE_ADDRESS__)
inline constexpr bool kSanitized = true;
#else
inline constexpr bool kSanitized = false;
#endif

}  // namespace trackphys::test
