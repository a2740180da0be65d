#include "trackphys/geometry/point_ellipsoid.hpp"

#include <cmath>

#include <glm/geometric.hpp>

#include "geometry/ellipsoid_roots.hpp"
#include "geometry/sorted_query_check.hpp"
#include "trackphys/assert.hpp"

namespace trackphys {
namespace {

glm::dvec3 to_vec(const std::array<double, 3>& a) { return {a[0], a[1], a[2]}; }

}  // namespace

PointEllipsoid closest_point_on_sorted_ellipsoid(const glm::dvec3& r, const glm::dvec3& p) {
    detail::check_sorted_query<3>("closest_point_on_sorted_ellipsoid", {r.x, r.y, r.z},
                                  {p.x, p.y, p.z});
    detail::CriticalSolver<3> solver({r.x, r.y, r.z}, {p.x, p.y, p.z});
    detail::CriticalPoints<3> found;
    solver.solve(detail::CriticalSet::closest, found);
    TP_ASSERT(found.count == 1, "every point has a closest surface point");
    const detail::CriticalPoint<3>& cp = found.points[0];
    return {to_vec(cp.x), to_vec(cp.n), cp.offset, found.iterations};
}

PointEllipsoid closest_point_on_ellipsoid(const Ellipsoid& ellipsoid, const glm::dvec3& p) {
    // The radii are sorted by construction; the point is checked as the caller gave it, so
    // that a refusal names this call and that point.
    const glm::dvec3& r = ellipsoid.sorted_radii();
    detail::check_sorted_query<3>("closest_point_on_ellipsoid", {r.x, r.y, r.z}, {p.x, p.y, p.z});
    const PointEllipsoid local =
        closest_point_on_sorted_ellipsoid(ellipsoid.sorted_radii(), ellipsoid.to_sorted_local(p));
    return {ellipsoid.center() + ellipsoid.sorted_direction_to_world(local.point),
            ellipsoid.sorted_direction_to_world(local.normal), local.distance, local.iterations};
}

EllipsoidCriticalPoints ellipsoid_critical_points(const glm::dvec3& r, const glm::dvec3& p) {
    detail::check_sorted_query<3>("ellipsoid_critical_points", {r.x, r.y, r.z}, {p.x, p.y, p.z});
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
