#pragma once

namespace trackphys::detail {

/// Whether this CPU (and its OS) runs AVX2, asked once: the cull, the face certificate and
/// the mid phase's filter take four lanes where it does (geometry/ellipsoid_cull_list.hpp,
/// geometry/face_certificate_lanes.hpp, collision/plane_tree.cpp).
/// TRACKPHYS_LANES=2 in the environment makes it answer false, so that the two-lane paths,
/// which an AVX2 machine never takes otherwise, run end to end in tests (the results must not
/// change: drive.pinned_state_hash_two_lanes). Beside cpu_runs_build_target, in
/// build_target.cpp.
bool cpu_has_avx2() noexcept;

}  // namespace trackphys::detail
