#pragma once

#include <glm/geometric.hpp>

#include "trackphys/geometry/ellipsoid.hpp"
#include "trackphys/geometry/normalized_triangle.hpp"

namespace trackphys {

/// Half-extent (m) of the ellipsoid along the unit direction u: its support function
/// h(u) = || D A^T u || with A the sorted axes and D the sorted radii.
inline double support_extent(const Ellipsoid& e, const glm::dvec3& u) {
    return glm::length(e.sorted_radii() * (u * e.sorted_axes()));
}

/// A tighter second cull after NormalizedTriangle::may_touch_sphere: a separating-axis test
/// on the triangle's own frame axes, normal first. Along each axis the triangle spans
/// [0, 0] (normal), [0, x1] (dir_x) or [0, y2] (dir_y) from its origin, and the ellipsoid
/// spans its centre's coordinate +- h(axis); disjoint spans on any axis prove the two apart.
/// false only if the ellipsoid cannot touch the triangle. A flat wheel is judged by its
/// width sideways, not by its radius, so far fewer neighbours of its footprint survive.
inline bool ellipsoid_may_touch(const NormalizedTriangle& t, const Ellipsoid& e) {
    const glm::dvec3 local = e.center() - t.origin;
    const double z = glm::dot(t.normal, local);
    const double hz = support_extent(e, t.normal);
    if (z > hz || z < -hz) return false;
    const double x = glm::dot(t.dir_x, local);
    const double hx = support_extent(e, t.dir_x);
    if (x < -hx || x > t.x1 + hx) return false;
    const double y = glm::dot(t.dir_y, local);
    const double hy = support_extent(e, t.dir_y);
    return y >= -hy && y <= t.y2 + hy;
}

}  // namespace trackphys
