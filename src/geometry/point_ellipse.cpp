#include "trackphys/geometry/point_ellipse.hpp"

#include "geometry/ellipsoid_roots.hpp"
#include "geometry/sorted_query_check.hpp"
#include "trackphys/assert.hpp"

namespace trackphys {
namespace {

EllipseCriticalPoint to_public(const detail::CriticalPoint<2>& cp) {
    return {{cp.x[0], cp.x[1]}, {cp.n[0], cp.n[1]}, cp.offset, cp.local_min};
}

}  // namespace

EllipseCriticalPoints ellipse_critical_points(const glm::dvec2& sorted_radii, const glm::dvec2& p) {
    detail::check_sorted_query<2>("ellipse_critical_points", {sorted_radii.x, sorted_radii.y},
                                  {p.x, p.y});
    detail::CriticalSolver<2> solver({sorted_radii.x, sorted_radii.y}, {p.x, p.y});
    detail::CriticalPoints<2> found;
    solver.solve(detail::CriticalSet::all, found);
    TP_ASSERT(found.count <= 4, "an ellipse has at most 4 critical points per query");
    EllipseCriticalPoints result{};
    result.count = found.count;
    result.iterations = found.iterations;
    for (int k = 0; k < found.count; ++k) result.points[k] = to_public(found.points[k]);
    return result;
}

EllipseCriticalPoint closest_point_on_ellipse(const glm::dvec2& sorted_radii, const glm::dvec2& p) {
    detail::check_sorted_query<2>("closest_point_on_ellipse", {sorted_radii.x, sorted_radii.y},
                                  {p.x, p.y});
    detail::CriticalSolver<2> solver({sorted_radii.x, sorted_radii.y}, {p.x, p.y});
    detail::CriticalPoints<2> found;
    solver.solve(detail::CriticalSet::closest, found);
    return to_public(found.points[0]);
}

}  // namespace trackphys
