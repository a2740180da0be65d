#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

#include "trackphys/geometry/ellipsoid.hpp"
#include "trackphys/geometry/normalized_triangle.hpp"
#include "trackphys/math/types.hpp"

namespace trackphys {

/// Half-extent (m) of the ellipsoid along the unit direction u: its support function
/// h(u) = || D A^T u || with A the sorted axes and D the sorted radii.
inline double support_extent(const Ellipsoid& e, const glm::dvec3& u) {
    return glm::length(e.sorted_radii() * (u * e.sorted_axes()));
}

/// The sub-step cull World runs on each listed triangle (tighter than
/// NormalizedTriangle::may_touch_sphere, which it implies): a separating-axis test on the
/// triangle's own frame axes. Along each axis the triangle spans
/// [0, 0] (normal), [0, x1] (dir_x) or [0, y2] (dir_y) from its origin, and the ellipsoid
/// spans its centre's coordinate +- h(axis); disjoint spans on any axis prove the two apart.
/// A flat wheel is judged by its width sideways, not by its radius, so far fewer
/// neighbours of its footprint survive.
///
/// Returns -infinity when the ellipsoid cannot touch the triangle, else an upper bound of
/// their penetration depth: sigma is the minimum of g over all directions, so it is at most
/// min(g(n), g(-n)) = h(n) - |n . (c - p)|, the depth along the triangle's normal. A
/// triangle whose bound is no deeper than a contact already found cannot be the deepest.
inline double ellipsoid_depth_bound(const NormalizedTriangle& t, const Ellipsoid& e) {
    const glm::dvec3 local = e.center() - t.origin;
    const double z = glm::dot(t.normal, local);
    const double x = glm::dot(t.dir_x, local);
    const double y = glm::dot(t.dir_y, local);
    // Nearly every listed triangle passes this test (a wheel's few listed triangles lie
    // around it): the three extents go together, with no branch between them, so that
    // their square roots overlap instead of waiting on each other.
    const double hz = support_extent(e, t.normal);
    const double hx = support_extent(e, t.dir_x);
    const double hy = support_extent(e, t.dir_y);
    const bool apart =
        (z > hz) | (z < -hz) | (x < -hx) | (x > t.x1 + hx) | (y < -hy) | (y > t.y2 + hy);
    return apart ? -std::numeric_limits<double>::infinity() : hz - std::abs(z);
}

/// An upper bound of the ellipsoid's penetration depth into the triangle from any unit
/// direction u, given its support h(u) = support_extent(e, u): sigma = min over unit u of
/// max_i u . (v_i - c) + h(u) (docs/design.md#exact-ellipsoid-triangle-contact), so every u
/// bounds it. With u the normal of the deepest contact found so far on a neighbouring
/// triangle, a triangle that lies lower along it (a coplanar or convex neighbour of the one
/// a wheel stands on) cannot be deeper, whatever its own normal says.
///
/// Read from the triangle's frame, as the cull reads it, so that the exact phase fetches no
/// vertices: they lie at the origin plus 0, x1 dir_x and x2 dir_x + y2 dir_y, and the bound
/// moves by the frame's rounding alone (a few eps of the lengths involved).
inline double depth_bound_along(const NormalizedTriangle& t, const Ellipsoid& e,
                                const glm::dvec3& u, double support) {
    const double along_x = glm::dot(u, t.dir_x);
    const double along_y = glm::dot(u, t.dir_y);
    return glm::dot(u, t.origin - e.center()) +
           std::max({0.0, t.x1 * along_x, t.x2 * along_x + t.y2 * along_y}) + support;
}

/// false only if the ellipsoid cannot touch the triangle (see ellipsoid_depth_bound).
inline bool ellipsoid_may_touch(const NormalizedTriangle& t, const Ellipsoid& e) {
    return ellipsoid_depth_bound(t, e) > -std::numeric_limits<double>::infinity();
}

}  // namespace trackphys
