#include "geometry/ellipsoid_cull_list.hpp"

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

}  // namespace trackphys::detail
