#pragma once

// FCL 0.7's GJK/EPA on two fcl::Ellipsoid, for the ellipsoid-pair peer comparison, with
// each of its two solvers (GST_LIBCCD: libccd GJK + MPR; GST_INDEP: FCL's own GJK + EPA):
// fcl::collide with one contact (its penetration depth; GST_INDEP reports it negated, so
// the magnitude is taken) and, when FCL reports no collision, fcl::distance for the gap.
// Default tolerances; shapes built per query.

#include <cmath>
#include <vector>

#include <fcl/geometry/shape/ellipsoid.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/distance.h>

#include "peers/ellipsoid_pair_peer_harness.hpp"

namespace trackphys::peers {

struct FclPairPose {
    fcl::Ellipsoidd shape;
    fcl::Transform3d transform;
    explicit FclPairPose(const Ellipsoid& e)
        : shape(fcl::Vector3d(e.semi_axes().x, e.semi_axes().y, e.semi_axes().z)),
          transform(fcl::Transform3d::Identity()) {
        const glm::dquat& q = e.orientation();
        transform.linear() = fcl::Quaterniond(q.w, q.x, q.y, q.z).toRotationMatrix();
        transform.translation() = fcl::Vector3d(e.center().x, e.center().y, e.center().z);
    }
};

inline PairPeer fcl_pair_peer(const char* name, fcl::GJKSolverType solver) {
    return {name, [solver](const Ellipsoid& a, const Ellipsoid& b) {
                const FclPairPose pa(a), pb(b);
                fcl::CollisionRequestd request(1, /*enable_contact=*/true);
                request.gjk_solver_type = solver;
                fcl::CollisionResultd result;
                fcl::collide(&pa.shape, pa.transform, &pb.shape, pb.transform, request, result);
                if (result.isCollision()) {
                    if (result.numContacts() == 0) return PairPeerDepth{0.0, true};
                    return PairPeerDepth{std::abs(result.getContact(0).penetration_depth), false};
                }
                fcl::DistanceRequestd distance_request;
                distance_request.gjk_solver_type = solver;
                fcl::DistanceResultd distance;
                fcl::distance(&pa.shape, pa.transform, &pb.shape, pb.transform, distance_request,
                              distance);
                return PairPeerDepth{-distance.min_distance, false};
            }};
}

/// Both solvers.
inline std::vector<PairPeer> fcl_pair_peers() {
    return {fcl_pair_peer("fcl_libccd_gjk_mpr", fcl::GJKSolverType::GST_LIBCCD),
            fcl_pair_peer("fcl_indep_gjk_epa", fcl::GJKSolverType::GST_INDEP)};
}

}  // namespace trackphys::peers
