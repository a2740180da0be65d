#pragma once

// The query shapes of PlaneTree: each knows whether it reaches a node's half-space and
// whether it touches a triangle (the per-triangle filter). Internal; the tests run the
// same filters over every triangle as the brute-force reference.

#include <algorithm>
#include <cmath>
#include <string>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include "collision/float_bounds.hpp"
#include "collision/triangle_predicates.hpp"
#include "trackphys/collision/plane_tree.hpp"
#include "trackphys/error.hpp"
#include "trackphys/geometry/ellipsoid.hpp"
#include "trackphys/geometry/normalized_triangle.hpp"
#include "trackphys/geometry/triangle.hpp"
#include "trackphys/math/types.hpp"

namespace trackphys::collision_detail {

// Plane tests use the shape grown by this fraction of its coordinate scale. The per-triangle
// filter and the node offsets are both computed in double from the same stored triangles;
// their rounding is a few ulps of the coordinates (~1e-16 relative), so 1e-10 guarantees
// that a triangle the filter accepts is never pruned by a plane above it, while it widens the
// planes by only 0.2 um at 2 km from the origin.
inline constexpr double kPlaneSlack = 1e-10;

inline double max_abs(const glm::dvec3& v) {
    return std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
}

inline glm::dvec3 node_normal(const PlaneTreeNode& node) {
    return {node.normal[0], node.normal[1], node.normal[2]};
}

/// A float at or below x (the largest).
inline float float_down(double x) { return round_down(x); }

/// A float at or above x (the smallest).
inline float float_up(double x) { return round_up(x); }

/// The float box of a triangle's vertices, rounded outward: float_down's and float_up's
/// floats, rounded in SSE2 lanes (a map load rounds a box for each of its triangles).
inline PlaneTreeBox float_box(const Triangle& t) {
    FloatBox outward, inward;
    round_both_ways(triangle_box(t[0], t[1], t[2]), outward, inward);
    return {{outward.min[0], outward.min[1], outward.min[2]},
            {outward.max[0], outward.max[1], outward.max[2]}};
}

/// True when the box [lo, hi] (a shape's, in double) meets a slot's box.
inline bool meets_box(const glm::dvec3& lo, const glm::dvec3& hi, const PlaneTreeBox& box) {
    return lo.x <= double(box.high[0]) && hi.x >= double(box.low[0]) &&
           lo.y <= double(box.high[1]) && hi.y >= double(box.low[1]) &&
           lo.z <= double(box.high[2]) && hi.z >= double(box.low[2]);
}

/// True when the interval [lo, hi] of a shape along a slab's normal, grown by `reach`,
/// meets the slab.
inline bool meets_slab(double lo, double hi, double reach, const PlaneTreeSlab& slab) {
    return lo - reach <= double(slab.high) && hi + reach >= double(slab.low);
}

/// A point in the triangle's own frame (x along dir_x, y along dir_y, z along the normal),
/// where the triangle is (0,0,0), (x1,0,0), (x2,y2,0).
inline glm::dvec3 to_local(const NormalizedTriangle& t, const glm::dvec3& p) {
    const glm::dvec3 d = p - t.origin;
    return {glm::dot(t.dir_x, d), glm::dot(t.dir_y, d), glm::dot(t.normal, d)};
}

/// Exact test of segment [a, b] against triangle (v0, v1, v2): distance <= sqrt(limit_sq).
/// A vertex or an edge that close settles it (the triangle is at least as close as any of
/// its points), cheapest first; only what is left pays for the full segment-triangle
/// distance (whose minimum is over these same features plus the face).
inline bool segment_within(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& v0,
                           const glm::dvec3& v1, const glm::dvec3& v2, double limit_sq) {
    if (point_segment_distance_squared(v0, a, b) <= limit_sq ||
        point_segment_distance_squared(v1, a, b) <= limit_sq ||
        point_segment_distance_squared(v2, a, b) <= limit_sq ||
        segment_segment_distance_squared(a, b, v0, v1) <= limit_sq ||
        segment_segment_distance_squared(a, b, v1, v2) <= limit_sq ||
        segment_segment_distance_squared(a, b, v2, v0) <= limit_sq)
        return true;
    return segment_triangle_distance_squared(a, b, v0, v1, v2) <= limit_sq;
}

/// A sphere moving along [start, end] (start == end for a plain sphere). Swept is a template
/// flag so that the plain sphere does one dot product a plane.
template <bool Swept>
struct SphereShape {
    glm::dvec3 start, end;
    double radius, radius_squared, node_radius;
    glm::dvec3 box_low, box_high;  // the swept shape's box, grown by the slack

    /// Throws trackphys::Error on non-finite points or a bad radius.
    SphereShape(const glm::dvec3& a, const glm::dvec3& b, double r) : start(a), end(b) {
        radius_squared = make_capsule_query(a, b, r).radius_squared;
        radius = r;
        node_radius = r + kPlaneSlack * (1.0 + std::max(max_abs(a), max_abs(b)) + r);
        box_low = glm::min(a, b) - node_radius;
        box_high = glm::max(a, b) + node_radius;
    }

    /// A triangle the filter accepts has a point within the radius of the segment, so inside
    /// the segment's box grown by it (and by the slack that covers the filter's rounding).
    bool reaches_box(const PlaneTreeBox& box) const { return meets_box(box_low, box_high, box); }

    /// The half-space {n.x <= offset} is reached when the shape's lowest point along n is
    /// in it: min over the segment of n.c, minus the radius (n has length <= 1).
    bool reaches(const PlaneTreeNode& node) const {
        const glm::dvec3 n = node_normal(node);
        double low = glm::dot(n, start);
        if constexpr (Swept) low = std::min(low, glm::dot(n, end));
        return low - node_radius <= double(node.offset);
    }

    bool reaches_slab(const PlaneTreeSlab& slab) const {
        const glm::dvec3 n(slab.normal[0], slab.normal[1], slab.normal[2]);
        const double a = glm::dot(n, start);
        const double b = Swept ? glm::dot(n, end) : a;
        return meets_slab(std::min(a, b), std::max(a, b), node_radius, slab);
    }

    /// The filter. Rejections first, each a lower bound of the distance over a convex set
    /// that holds the triangle (so it rejects only what the exact test rejects): the plane,
    /// the local box [0, x1] x [0, y2] within the plane, and each slanted edge's half-plane
    /// within the plane. Over a segment, distance^2 to such a set is a sum of squared gaps
    /// that are each linear in the segment parameter, so the sum of each gap's minimum
    /// (at an endpoint, or 0 if the gap changes sign) bounds it from below. Then sure
    /// accepts (an endpoint over the triangle, a vertex within the radius) and the exact
    /// segment-triangle distance for the few left.
    bool touches(const NormalizedTriangle& t) const {
        const glm::dvec3 a = to_local(t, start);
        const glm::dvec3 b = Swept ? to_local(t, end) : a;
        const glm::dvec3 lo = glm::min(a, b), hi = glm::max(a, b);
        const double z_gap = lo.z > 0.0 ? lo.z : (hi.z < 0.0 ? -hi.z : 0.0);
        const double x_gap = std::max({lo.x - t.x1, -hi.x, 0.0});
        const double y_gap = std::max({lo.y - t.y2, -hi.y, 0.0});
        const double z_sq = z_gap * z_gap;
        if (z_sq + x_gap * x_gap + y_gap * y_gap > radius_squared) return false;
        // In-plane outward edge functions of the edges (0,0)-(x2,y2) and (x1,0)-(x2,y2):
        // |edge| times the signed distance to the edge's line (negative inside).
        const double ex = t.x2 - t.x1;
        auto edge1 = [&](const glm::dvec3& p) { return t.x2 * p.y - t.y2 * p.x; };
        auto edge2 = [&](const glm::dvec3& p) { return (p.x - t.x1) * t.y2 - p.y * ex; };
        const double e1 = std::min(edge1(a), edge1(b)), e2 = std::min(edge2(a), edge2(b));
        const double plane_sq = radius_squared - z_sq;
        if ((e1 > 0.0 && e1 * e1 > plane_sq * (t.x2 * t.x2 + t.y2 * t.y2)) ||
            (e2 > 0.0 && e2 * e2 > plane_sq * (ex * ex + t.y2 * t.y2)))
            return false;
        auto over = [&](const glm::dvec3& p) {
            return p.y >= 0.0 && edge1(p) <= 0.0 && edge2(p) <= 0.0 && std::abs(p.z) <= radius;
        };
        if (over(a) || (Swept && over(b))) return true;
        return segment_within(a, b, glm::dvec3(0.0), {t.x1, 0.0, 0.0}, {t.x2, t.y2, 0.0},
                              radius_squared);
    }
};

/// An ellipsoid (center start, world-from-local rotation Q, semi-axes D) moving along
/// [start, end]. Its support along u is h(u) = ||D Q^T u|| = sqrt(u^T M u), M = Q D^2 Q^T,
/// so its half-space test is as exact as the sphere's. The map x -> D^-1 Q^T (x - start)
/// sends it to the unit ball moving along [0, D^-1 Q^T (end - start)], where touching a
/// triangle is a segment-triangle distance <= 1.
struct EllipsoidShape {
    glm::dvec3 start, end;
    double m00, m11, m22, m01, m02, m12;  // M, symmetric
    glm::dmat3 to_unit;                   // D^-1 Q^T
    glm::dvec3 unit_end;                  // to_unit * (end - start)
    double slack;
    double reach_squared;          // above support_squared(u) for any |u| <= 1
    glm::dvec3 box_low, box_high;  // the swept ellipsoid's box, grown by the slack

    /// The ellipsoid scaled about its center by 1 + margin / (smallest semi-axis). Throws
    /// trackphys::Error on a non-finite end or a bad margin.
    EllipsoidShape(const Ellipsoid& e, const glm::dvec3& end_center, double margin)
        : start(e.center()), end(end_center) {
        if (!is_finite(end_center))
            throw Error("plane tree swept-ellipsoid query: end center is not finite");
        if (!std::isfinite(margin) || !(margin >= 0.0))
            throw Error("plane tree swept-ellipsoid query: margin must be finite and >= 0, got " +
                        exact_text(margin));
        const glm::dvec3 radii = e.sorted_radii() * (1.0 + margin / e.sorted_radii().z);
        // M = sum_k r_k^2 q_k q_k^T over the sorted axes q_k (columns); the unit-ball map's
        // rows are q_k / r_k.
        const glm::dmat3& q = e.sorted_axes();
        m00 = m11 = m22 = m01 = m02 = m12 = 0.0;
        for (int k = 0; k < 3; ++k) {
            const glm::dvec3& axis = q[k];
            const double r2 = radii[k] * radii[k];
            m00 += r2 * axis.x * axis.x;
            m11 += r2 * axis.y * axis.y;
            m22 += r2 * axis.z * axis.z;
            m01 += r2 * axis.x * axis.y;
            m02 += r2 * axis.x * axis.z;
            m12 += r2 * axis.y * axis.z;
            const glm::dvec3 row = axis / radii[k];
            for (int c = 0; c < 3; ++c) to_unit[c][k] = row[c];
        }
        unit_end = to_unit * (end - start);
        // Rounding in the unit-ball frame is relative to that frame's coordinates, which
        // stretch world lengths by up to 1 / (smallest radius): the slack scales with it.
        slack = kPlaneSlack * (1.0 + std::max(max_abs(start), max_abs(end)) + radii.x) *
                (radii.x / radii.z);
        // h(u) <= r_x |u|, and every direction tested against it has |u| <= 1 (the tree's
        // normals are rounded toward zero, the triangle's axes are unit) up to rounding far
        // below the factor's room: a gap beyond it is rejected without computing h(u)^2,
        // only where the comparison with h(u)^2 would reject it too.
        reach_squared = radii.x * radii.x * (1.0 + 1e-6);
        // The ellipsoid reaches h(e_k) = sqrt(M_kk) along each axis; 1e-6 of room covers
        // the rounding of M and of the square root, as reach_squared's does.
        const glm::dvec3 half(std::sqrt(m00), std::sqrt(m11), std::sqrt(m22));
        box_low = glm::min(start, end) - half * (1.0 + 1e-6) - slack;
        box_high = glm::max(start, end) + half * (1.0 + 1e-6) + slack;
    }

    /// A triangle the filter accepts meets the swept ellipsoid, so its box meets the sweep's.
    bool reaches_box(const PlaneTreeBox& box) const { return meets_box(box_low, box_high, box); }

    double support_squared(const glm::dvec3& u) const {
        return m00 * u.x * u.x + m11 * u.y * u.y + m22 * u.z * u.z +
               2.0 * (m01 * u.x * u.y + m02 * u.x * u.z + m12 * u.y * u.z);
    }

    /// low - h(n) - slack <= offset, without the square root: a shape whose lowest center
    /// is already inside passes at once, otherwise compare squares of non-negative sides.
    bool reaches(const PlaneTreeNode& node) const {
        const glm::dvec3 n = node_normal(node);
        const double gap =
            std::min(glm::dot(n, start), glm::dot(n, end)) - slack - double(node.offset);
        return gap <= 0.0 || (gap * gap <= reach_squared && gap * gap <= support_squared(n));
    }

    /// The slab is missed when the shape's interval along its normal lies beyond one of its
    /// faces by more than h(n) + slack; at most one of the two gaps is positive, and as in
    /// reaches() the squares are compared instead of taking the square root.
    bool reaches_slab(const PlaneTreeSlab& slab) const {
        const glm::dvec3 n(slab.normal[0], slab.normal[1], slab.normal[2]);
        const double a = glm::dot(n, start), b = glm::dot(n, end);
        const double gap = std::max(std::min(a, b) - slack - double(slab.high),
                                    double(slab.low) - std::max(a, b) - slack);
        return gap <= 0.0 || (gap * gap <= reach_squared && gap * gap <= support_squared(n));
    }

    /// The filter: the triangle's plane and local box first (the ellipsoid's reach along
    /// each frame axis is its support there; squares compared only for positive gaps), then
    /// the exact test in the unit-ball frame.
    bool touches(const NormalizedTriangle& t) const {
        // One frame axis at a time, each rejecting before the next is computed: the same
        // values as to_local's.
        const glm::dvec3 from_a = start - t.origin, from_b = end - t.origin;
        const double az = glm::dot(t.normal, from_a), bz = glm::dot(t.normal, from_b);
        const double z_lo = std::min(az, bz), z_hi = std::max(az, bz);
        const double z_gap = std::max({z_lo, -z_hi, 0.0});
        // h(n)^2, which the sure accept below needs too: a wheel's shape lies above its
        // road, so the plane test nearly always pays for it anyway.
        const double h_sq = support_squared(t.normal);
        if (z_gap > 0.0 && z_gap * z_gap > h_sq) return false;
        const double ax = glm::dot(t.dir_x, from_a), bx = glm::dot(t.dir_x, from_b);
        const double x_gap = std::max({std::min(ax, bx) - t.x1, -std::max(ax, bx), 0.0});
        if (x_gap > 0.0 &&
            (x_gap * x_gap > reach_squared || x_gap * x_gap > support_squared(t.dir_x)))
            return false;
        const double ay = glm::dot(t.dir_y, from_a), by = glm::dot(t.dir_y, from_b);
        const double y_gap = std::max({std::min(ay, by) - t.y2, -std::max(ay, by), 0.0});
        if (y_gap > 0.0 &&
            (y_gap * y_gap > reach_squared || y_gap * y_gap > support_squared(t.dir_y)))
            return false;
        const glm::dvec3 a(ax, ay, az), b(bx, by, bz);
        const double ex = t.x2 - t.x1;
        // Sure accept, the common wheel-on-road case: from a center c at height z over the
        // plane, the chord x = c - (z / n^T M n) M n stays in the ellipsoid while
        // z^2 <= n^T M n (its M^-1 norm is |z| / h(n)) and ends on the plane; if it ends over
        // the triangle, they touch. Along the sweep c(t) = a + t (b - a) the chord's foot
        // moves linearly in t, so the t in [0, 1] where it exists and lies over the triangle
        // form an interval: [0, 1] clipped by |z(t)| <= h(n) and the three edges'
        // half-planes. It catches the triangles a wheel rolls over mid-sweep, not only
        // those under its ends. It comes before the edge and tilted-axis rejections below:
        // those are exact bounds too, so the order leaves every answer unchanged, and far
        // more calls end here than there.
        const double h = std::sqrt(h_sq);
        const glm::dvec3 mn(m00 * t.normal.x + m01 * t.normal.y + m02 * t.normal.z,
                            m01 * t.normal.x + m11 * t.normal.y + m12 * t.normal.z,
                            m02 * t.normal.x + m12 * t.normal.y + m22 * t.normal.z);
        const double mn_x = glm::dot(t.dir_x, mn) / h_sq, mn_y = glm::dot(t.dir_y, mn) / h_sq;
        const double xa = a.x - a.z * mn_x, ya = a.y - a.z * mn_y;
        const double xb = b.x - b.z * mn_x, yb = b.y - b.z * mn_y;
        double first = 0.0, last = 1.0;
        // Keeps the t with f(t) = fa + t (fb - fa) <= 0.
        auto keep_below = [&](double fa, double fb) {
            if (fa <= 0.0 && fb <= 0.0) return;
            if (fa > 0.0 && fb > 0.0)
                first = 2.0;
            else if (fa > 0.0)
                first = std::max(first, fa / (fa - fb));
            else
                last = std::min(last, fa / (fa - fb));
        };
        keep_below(a.z - h, b.z - h);
        keep_below(-a.z - h, -b.z - h);
        keep_below(-ya, -yb);
        keep_below(t.x2 * ya - t.y2 * xa, t.x2 * yb - t.y2 * xb);
        keep_below((xa - t.x1) * t.y2 - ya * ex, (xb - t.x1) * t.y2 - yb * ex);
        if (first <= last) return true;
        // The slanted edges' half-planes: e / |edge| is the in-plane distance beyond the
        // edge's line along the world direction u = (x2 dir_y - y2 dir_x) / |edge| (and
        // likewise for the other edge), where the ellipsoid reaches h(u).
        const double e1 = std::min(t.x2 * a.y - t.y2 * a.x, t.x2 * b.y - t.y2 * b.x);
        const double e2 = std::min((a.x - t.x1) * t.y2 - a.y * ex, (b.x - t.x1) * t.y2 - b.y * ex);
        if ((e1 > 0.0 && e1 * e1 > support_squared(t.x2 * t.dir_y - t.y2 * t.dir_x)) ||
            (e2 > 0.0 && e2 * e2 > support_squared(t.y2 * t.dir_x - ex * t.dir_y)))
            return false;
        // Tilted separating axes, for a shape on one side of the plane (sign s): along
        // d = U + s lambda n, with U an edge's outward in-plane normal (times the edge's
        // length, so f(p) = U.p - offset <= 0 on the triangle) and any lambda > 0 (about
        // 45 degrees here), the triangle reaches at most offset while the shape reaches
        // down to min over the ends of (U.p + s lambda z) - h(d). This separates a wheel
        // from the triangle beside the one it stands on, which the plane and the edge
        // alone do not.
        if (z_lo > 0.0 || z_hi < 0.0) {
            const double side = z_lo > 0.0 ? 1.0 : -1.0;
            auto separated = [&](double ux, double uy, double offset, double lambda) {
                const double sl = side * lambda;
                const double m =
                    std::min(ux * a.x + uy * a.y + sl * a.z, ux * b.x + uy * b.y + sl * b.z) -
                    offset;
                return m > 0.0 &&
                       m * m > support_squared(ux * t.dir_x + uy * t.dir_y + sl * t.normal);
            };
            if (separated(0.0, -t.x1, 0.0, t.x1) ||
                separated(-t.y2, t.x2, 0.0, std::abs(t.x2) + t.y2) ||
                separated(t.y2, -ex, t.x1 * t.y2, std::abs(ex) + t.y2))
                return false;
        }
        return touches_exactly(t);
    }

    /// The filter's last word, for what its bounds leave undecided: the segment-triangle
    /// distance in the unit-ball frame.
    bool touches_exactly(const NormalizedTriangle& t) const {
        return segment_within(glm::dvec3(0.0), unit_end, to_unit * (t.vertex(0) - start),
                              to_unit * (t.vertex(1) - start), to_unit * (t.vertex(2) - start),
                              1.0);
    }
};

}  // namespace trackphys::collision_detail
