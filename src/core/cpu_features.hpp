#pragma once

namespace trackphys::detail {

/// Whether this CPU (and its OS) runs AVX2, asked once: the cull takes four lanes where it
/// does (geometry/ellipsoid_cull_list.hpp). Beside cpu_runs_build_target, in build_target.cpp.
bool cpu_has_avx2() noexcept;

}  // namespace trackphys::detail
