#pragma once

// FCL 0.7's ellipsoid vs triangle against ours on the same cases, with each of FCL's two GJK
// solvers (GST_LIBCCD: libccd GJK + MPR; GST_INDEP: FCL's own GJK + EPA).
//
// FCL's public fcl::distance / fcl::collide do not dispatch fcl::Ellipsoid (node type 11)
// vs fcl::TriangleP (18): they print "... function between node type 11 and node type 18
// is not supported" and answer nothing. Two ways remain, both measured:
// - "<solver>_triangle": FCL's narrow-phase solvers (fcl::detail::GJKSolver_libccd /
//   GJKSolver_indep) called directly, as FCL's own mesh-vs-shape traversal does:
//   shapeTriangleIntersect (penetration depth; GJKSolver_indep reports it negated,
//   -epa.depth, libccd positive: the magnitude is taken) and, when it reports no
//   intersection, shapeTriangleDistance for the gap;
// - "<solver>_convex_signed" / "<solver>_convex_collide": the triangle as an fcl::Convex
//   (three vertices, both faces; built before timing, as a user keeps shapes), through the
//   public API: fcl::distance with enable_signed_distance (depth = -min_distance), or
//   fcl::collide with enable_contact and one contact (its penetration_depth, negated by
//   GJKSolver_indep as above: the magnitude is taken) and, when FCL reports no collision,
//   fcl::distance for the gap. GJKSolver_indep has no real signed
//   distance ("TODO: should implement the signed distance version": -1 when overlapping),
//   so its signed variant is left out.
// Solvers keep FCL's default tolerances; shapes are built per query from the case.
//
//   (header-only: bench_peers_contact_fcl and trackphys-bench run the same methods)

#include <cmath>
#include <memory>
#include <vector>

#include <fcl/geometry/shape/convex.h>
#include <fcl/geometry/shape/ellipsoid.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/detail/gjk_solver_indep.h>
#include <fcl/narrowphase/detail/gjk_solver_libccd.h>
#include <fcl/narrowphase/distance.h>

#include "peers/contact_peer_harness.hpp"

namespace trackphys::peers::fcl_adapters {

inline fcl::Vector3d eigen(const glm::dvec3& v) { return {v.x, v.y, v.z}; }

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

/// The triangle as an fcl::Convex: its three vertices and the face both ways round (FCL's
/// GJK reads only the vertices).
inline fcl::Convexd convex_triangle(const trackphys::Triangle& t) {
    auto vertices = std::make_shared<const std::vector<fcl::Vector3d>>(
        std::vector<fcl::Vector3d>{eigen(t[0]), eigen(t[1]), eigen(t[2])});
    auto faces = std::make_shared<const std::vector<int>>(std::vector<int>{3, 0, 1, 2, 3, 0, 2, 1});
    return fcl::Convexd(vertices, 2, faces);
}

inline double gap(const Pose& pose, const fcl::Convexd& convex, fcl::GJKSolverType solver,
                  bool signed_distance) {
    fcl::DistanceRequestd request;
    request.enable_signed_distance = signed_distance;
    request.gjk_solver_type = solver;
    fcl::DistanceResultd result;
    fcl::distance(&pose.ellipsoid, pose.transform, &convex, fcl::Transform3d::Identity(), request,
                  result);
    return result.min_distance;
}

/// Ellipsoid vs the triangle as a convex through fcl::distance (signed) or fcl::collide.
inline Peer convex_peer(std::string name, fcl::GJKSolverType solver, bool signed_distance) {
    return {std::move(name), [=](const CaseSet& set) {
                auto convexes = std::make_shared<std::vector<fcl::Convexd>>();
                for (const PeerCase& c : set.cases)
                    convexes->push_back(convex_triangle(c.triangle));
                return std::function<PeerDepth(std::size_t)>([=, &set](std::size_t i) {
                    const Pose pose(set.cases[i].ellipsoid);
                    const fcl::Convexd& convex = (*convexes)[i];
                    if (signed_distance) return PeerDepth{-gap(pose, convex, solver, true), false};
                    fcl::CollisionRequestd request(1, /*enable_contact=*/true);
                    request.gjk_solver_type = solver;
                    fcl::CollisionResultd result;
                    fcl::collide(&pose.ellipsoid, pose.transform, &convex,
                                 fcl::Transform3d::Identity(), request, result);
                    if (!result.isCollision())
                        return PeerDepth{-gap(pose, convex, solver, false), false};
                    if (result.numContacts() == 0) return PeerDepth{0.0, true};
                    return PeerDepth{std::abs(result.getContact(0).penetration_depth), false};
                });
            }};
}

}  // namespace trackphys::peers::fcl_adapters

namespace trackphys::peers {

/// FCL's five methods above, in table order. The solvers live as long as the peers.
inline std::vector<Peer> fcl_contact_peers() {
    using namespace fcl_adapters;
    using fcl::GJKSolverType;
    const auto libccd = std::make_shared<const fcl::detail::GJKSolver_libccdd>();
    const auto indep = std::make_shared<const fcl::detail::GJKSolver_indepd>();
    return {per_case("fcl_libccd_triangle",
                     [libccd](const PeerCase& c) { return triangle_query(*libccd, c); }),
            per_case("fcl_indep_triangle",
                     [indep](const PeerCase& c) { return triangle_query(*indep, c); }),
            convex_peer("fcl_libccd_convex_signed", GJKSolverType::GST_LIBCCD, true),
            convex_peer("fcl_libccd_convex_collide", GJKSolverType::GST_LIBCCD, false),
            convex_peer("fcl_indep_convex_collide", GJKSolverType::GST_INDEP, false)};
}

}  // namespace trackphys::peers
