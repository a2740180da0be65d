#include "trackphys/build_target.hpp"

namespace trackphys {

const char* build_target() noexcept {
#if defined(__x86_64__) && defined(__SSE4_2__)
    return "x86-64-v2";
#elif defined(__x86_64__)
    return "x86-64";
#else
    return "portable";
#endif
}

bool cpu_runs_build_target() noexcept {
#if defined(__x86_64__) && defined(__SSE4_2__)
    __builtin_cpu_init();
    return __builtin_cpu_supports("ssse3") && __builtin_cpu_supports("sse4.1") &&
           __builtin_cpu_supports("sse4.2") && __builtin_cpu_supports("popcnt");
#else
    return true;
#endif
}

}  // namespace trackphys
