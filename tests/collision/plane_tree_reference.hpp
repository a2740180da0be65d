#pragma once

// Long-double references for the plane tree and mid-phase tests: the exact distance from a
// segment to a triangle, in world space (swept sphere) and in an ellipsoid's unit-ball
// frame (swept ellipsoid), and the brute-force scan with the tree's own filter.

#include <algorithm>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "collision/plane_tree_shapes.hpp"
#include "support/closest_point_reference.hpp"
#include "trackphys/collision/plane_tree.hpp"
#include "trackphys/geometry/ellipsoid.hpp"
#include "trackphys/geometry/normalized_triangle.hpp"

namespace trackphys::test {

/// Distance from the segment [s0, s1] to the triangle, all in long double: the distance
/// from a point moving along a line to a convex set is convex in the line parameter, so a
/// ternary search converges to its minimum ((2/3)^120 of the segment, ~1e-21 relative).
inline long double segment_triangle_distance(LVec s0, LVec s1, LVec a, LVec b, LVec c) {
    auto at = [&](long double t) {
        const LVec p = s0 + (s1 - s0) * t;
        return length(p - closest_point_on_triangle(p, a, b, c));
    };
    long double lo = 0.0L, hi = 1.0L;
    for (int i = 0; i < 120; ++i) {
        const long double m1 = lo + (hi - lo) / 3.0L, m2 = hi - (hi - lo) / 3.0L;
        if (at(m1) <= at(m2))
            hi = m2;
        else
            lo = m1;
    }
    return std::min({at(0.0L), at(1.0L), at(0.5L * (lo + hi))});
}

inline long double swept_sphere_distance(const glm::dvec3& start, const glm::dvec3& end,
                                         const Triangle& t) {
    return segment_triangle_distance(lvec(start), lvec(end), lvec(t[0]), lvec(t[1]), lvec(t[2]));
}

/// The swept ellipsoid (scaled about its center by `scale`) touches the triangle iff this
/// is <= 1: the segment-triangle distance in the frame x -> D^-1 Q^T (x - center).
inline long double swept_ellipsoid_distance(const Ellipsoid& e, double scale, const glm::dvec3& end,
                                            const Triangle& t) {
    const glm::dmat3& q = e.sorted_axes();
    auto map = [&](const glm::dvec3& p) {
        const LVec d = lvec(p) - lvec(e.center());
        LVec out{};
        long double* o[3] = {&out.x, &out.y, &out.z};
        for (int k = 0; k < 3; ++k)
            *o[k] = dot(lvec(q[k]), d) / ((long double)e.sorted_radii()[k] * scale);
        return out;
    };
    return segment_triangle_distance(map(e.center()), map(end), map(t[0]), map(t[1]), map(t[2]));
}

/// Every slot of the tree whose triangle passes the tree's own filter for `shape`, in slot
/// order: what a query must return.
template <class Shape>
std::vector<std::uint32_t> brute_force_slots(const PlaneTree& tree, const Shape& shape) {
    std::vector<std::uint32_t> out;
    for (std::uint32_t slot = 0; slot < tree.triangle_count(); ++slot)
        if (shape.touches(tree.triangle(slot))) out.push_back(slot);
    return out;
}

}  // namespace trackphys::test
