// FCL 0.7's ellipsoid vs triangle against ours on the same cases, with each of FCL's two GJK
// solvers (GST_LIBCCD: libccd GJK + MPR; GST_INDEP: FCL's own GJK + EPA).
//
// FCL's public fcl::distance / fcl::collide do not dispatch this pair: for fcl::Ellipsoid
// (node type 11) vs fcl::TriangleP (18) they print "... function between node type 11 and
// node type 18 is not supported" and answer nothing. So the programs call FCL's
// narrow-phase solvers (fcl::detail::GJKSolver_libccd / GJKSolver_indep) directly, the way
// FCL's own mesh-vs-shape traversal does:
// - "<solver>_triangle": shapeTriangleIntersect (penetration depth; GJKSolver_indep reports it
//   negated, -epa.depth, libccd positive: the magnitude is taken) and, when it reports no
//   intersection, shapeTriangleDistance for the gap - FCL's ellipsoid vs mesh triangle path.
// FCL 0.7 has no signed distance for this pair: GJKSolver_indep::shapeSignedDistance is
// its plain distance (-1 when overlapping, "TODO: should implement the signed distance
// version"), and libccd's has no GJKInitializer for TriangleP.
// Solvers keep FCL's default tolerances; shapes are built per query from the case.
//
//   build/release/bench/bench_peers_contact_fcl [--quick] [--json FILE]

#include <cmath>

#include <fcl/geometry/shape/ellipsoid.h>
#include <fcl/narrowphase/detail/gjk_solver_indep.h>
#include <fcl/narrowphase/detail/gjk_solver_libccd.h>

#include "peers/contact_peer_harness.hpp"

namespace {

using trackphys::peers::PeerCase;
using trackphys::peers::PeerDepth;

fcl::Vector3d eigen(const glm::dvec3& v) { return {v.x, v.y, v.z}; }

/// The ellipsoid and its pose (local -> world).
struct Pose {
    fcl::Ellipsoidd ellipsoid;
    fcl::Transform3d transform;

    explicit Pose(const trackphys::Ellipsoid& e)
        : ellipsoid(eigen(e.semi_axes())), transform(fcl::Transform3d::Identity()) {
        const glm::dquat& q = e.orientation();
        transform.linear() = fcl::Quaterniond(q.w, q.x, q.y, q.z).toRotationMatrix();
        transform.translation() = eigen(e.center());
    }
};

template <class Solver>
PeerDepth triangle_query(const Solver& solver, const PeerCase& c) {
    const Pose pose(c.ellipsoid);
    const fcl::Vector3d a = eigen(c.triangle[0]), b = eigen(c.triangle[1]),
                        d = eigen(c.triangle[2]);
    double depth = 0.0;
    fcl::Vector3d point, normal;
    if (solver.shapeTriangleIntersect(pose.ellipsoid, pose.transform, a, b, d, &point, &depth,
                                      &normal))
        return {std::abs(depth), false};
    double distance = 0.0;
    if (!solver.shapeTriangleDistance(pose.ellipsoid, pose.transform, a, b, d, &distance))
        return {0.0, true};  // no intersection found, yet no distance either
    return {-distance, false};
}

}  // namespace

int main(int argc, char** argv) {
    const fcl::detail::GJKSolver_libccdd libccd;
    const fcl::detail::GJKSolver_indepd indep;
    return trackphys::peers::run_contact_peers(
        argc, argv, "bench_peers_contact_fcl",
        {{"fcl_libccd_triangle", [&](const PeerCase& c) { return triangle_query(libccd, c); }},
         {"fcl_indep_triangle", [&](const PeerCase& c) { return triangle_query(indep, c); }}});
}
