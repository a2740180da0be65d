#include "trackphys/geometry/point_ellipsoid.hpp"

#include <cmath>

#include <glm/geometric.hpp>

#include "geometry/ellipsoid_roots.hpp"
#include "geometry/writeup_root_finders.hpp"
#include "trackphys/assert.hpp"

namespace trackphys {
namespace {

glm::dvec3 to_vec(const std::array<double, 3>& a) { return {a[0], a[1], a[2]}; }

/// The closest point from the largest root t of f, as the write-up computes it.
PointEllipsoid from_largest_root(const glm::dvec3& r, const glm::dvec3& p,
                                 const detail::LargestRoot& root) {
    PointEllipsoid result{};
    glm::dvec3 n;
    for (int i = 0; i < 3; ++i) {
        const double w = r[i] * r[i] + root.t;
        result.point[i] = r[i] * r[i] * p[i] / w;
        n[i] = p[i] / w;
    }
    result.normal = glm::normalize(n);
    const double distance = glm::distance(p, result.point);
    result.distance = root.t < 0.0 ? -distance : distance;
    result.iterations = root.iterations;
    return result;
}

}  // namespace

PointEllipsoid closest_point_on_sorted_ellipsoid(const glm::dvec3& r, const glm::dvec3& p,
                                                 RootFinder finder) {
    switch (finder) {
        case RootFinder::bisection:
            return from_largest_root(r, p, detail::writeup_bisection_largest_root(r, p));
        case RootFinder::writeup_newton:
            return from_largest_root(r, p, detail::writeup_newton_largest_root(r, p));
        case RootFinder::robust:
            break;
    }
    detail::CriticalSolver<3> solver({r.x, r.y, r.z}, {p.x, p.y, p.z});
    detail::CriticalPoints<3> found;
    solver.solve(detail::CriticalSet::closest, found);
    TP_ASSERT(found.count == 1, "every point has a closest surface point");
    const detail::CriticalPoint<3>& cp = found.points[0];
    return {to_vec(cp.x), to_vec(cp.n), cp.offset, found.iterations};
}

PointEllipsoid closest_point_on_ellipsoid(const Ellipsoid& ellipsoid, const glm::dvec3& p,
                                          RootFinder finder) {
    const PointEllipsoid local = closest_point_on_sorted_ellipsoid(
        ellipsoid.sorted_radii(), ellipsoid.to_sorted_local(p), finder);
    return {ellipsoid.center() + ellipsoid.sorted_direction_to_world(local.point),
            ellipsoid.sorted_direction_to_world(local.normal), local.distance, local.iterations};
}

PointEllipsoid closest_point_on_ellipsoid(const Ellipsoid& ellipsoid, const glm::dvec3& p) {
    return closest_point_on_ellipsoid(ellipsoid, p, RootFinder::robust);
}

EllipsoidCriticalPoints ellipsoid_critical_points(const glm::dvec3& r, const glm::dvec3& p) {
    detail::CriticalSolver<3> solver({r.x, r.y, r.z}, {p.x, p.y, p.z});
    detail::CriticalPoints<3> found;
    solver.solve(detail::CriticalSet::all, found);
    EllipsoidCriticalPoints result{};
    result.count = found.count;
    result.iterations = found.iterations;
    for (int k = 0; k < found.count; ++k) {
        const detail::CriticalPoint<3>& cp = found.points[k];
        result.points[k] = {to_vec(cp.x), to_vec(cp.n), cp.offset, cp.local_min};
    }
    return result;
}

}  // namespace trackphys
