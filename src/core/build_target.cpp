#include "trackphys/build_target.hpp"

#include <cstdlib>
#include <string_view>

#include "core/cpu_features.hpp"

namespace trackphys {

// From the compiler's own macros, so that the answer is what this code was compiled for
// (with TRACKPHYS_X86_64_LEVEL=none and -march=native too).
const char* build_target() noexcept {
#if defined(__SSE4_2__)
    return "x86-64-v2";
#else
    return "x86-64";
#endif
}

bool cpu_runs_build_target() noexcept {
#if defined(__SSE4_2__)
    __builtin_cpu_init();
    return __builtin_cpu_supports("sse3") && __builtin_cpu_supports("ssse3") &&
           __builtin_cpu_supports("sse4.1") && __builtin_cpu_supports("sse4.2") &&
           __builtin_cpu_supports("popcnt");
#else
    return true;
#endif
}

}  // namespace trackphys

namespace trackphys::detail {

bool cpu_has_avx2() noexcept {
#if defined(__x86_64__) || defined(__i386__)
    // libgcc's and compiler-rt's answers include the OS's: it saves the 32-byte registers.
    static const bool has = [] {
        __builtin_cpu_init();
        return __builtin_cpu_supports("avx2") != 0;
    }();
    return has;
#else
    return false;
#endif
}

bool use_four_lanes() noexcept {
    static const bool four = [] {
        const char* lanes = std::getenv("TRACKPHYS_LANES");
        return cpu_has_avx2() && !(lanes != nullptr && std::string_view(lanes) == "2");
    }();
    return four;
}

}  // namespace trackphys::detail
