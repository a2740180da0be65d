#pragma once

namespace trackphys::detail {

/// Whether this CPU (and its OS) runs AVX2, asked once. Beside cpu_runs_build_target, in
/// build_target.cpp.
bool cpu_has_avx2() noexcept;

/// Whether the cull, the face certificate and the mid phase's filter take four lanes
/// (geometry/ellipsoid_cull_list.hpp, geometry/face_certificate_lanes.hpp,
/// collision/plane_tree.cpp): where the CPU runs AVX2, unless TRACKPHYS_LANES=2 is in the
/// environment, which sends an AVX2 machine down the two-lane paths it never takes otherwise,
/// so that tests run them end to end (the results must not change:
/// drive.pinned_state_hash_two_lanes). Asked once.
bool use_four_lanes() noexcept;

}  // namespace trackphys::detail
