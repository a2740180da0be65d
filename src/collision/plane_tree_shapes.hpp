#pragma once

// The query shapes of PlaneTree: each knows whether it reaches a node's half-space and
// whether it touches a triangle (the per-triangle filter). Internal; the tests run the
// same filters over every triangle as the brute-force reference.

#include <algorithm>
#include <cmath>
#include <string>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include "collision/triangle_predicates.hpp"
#include "trackphys/collision/plane_tree.hpp"
#include "trackphys/error.hpp"
#include "trackphys/geometry/ellipsoid.hpp"
#include "trackphys/geometry/normalized_triangle.hpp"
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

/// True when the interval [lo, hi] grown by `reach` misses [0, extent].
inline bool misses(double lo, double hi, double reach, double extent) {
    return lo > extent + reach || hi < -reach;
}

/// Exact test of segment [a, b] against triangle (v0, v1, v2): distance <= sqrt(limit_sq).
/// A vertex that close settles it cheaply (the triangle is at least as close as its
/// vertices); only the rest pay for the full segment-triangle distance.
inline bool segment_within(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& v0,
                           const glm::dvec3& v1, const glm::dvec3& v2, double limit_sq) {
    if (point_segment_distance_squared(v0, a, b) <= limit_sq ||
        point_segment_distance_squared(v1, a, b) <= limit_sq ||
        point_segment_distance_squared(v2, a, b) <= limit_sq)
        return true;
    return segment_triangle_distance_squared(a, b, v0, v1, v2) <= limit_sq;
}

/// A sphere moving along [start, end] (start == end for a plain sphere). Swept is a template
/// flag so that the plain sphere does one dot product a plane.
template <bool Swept>
struct SphereShape {
    glm::dvec3 start, end;
    double radius, radius_squared, node_radius;

    /// Throws trackphys::Error on non-finite points or a bad radius.
    SphereShape(const glm::dvec3& a, const glm::dvec3& b, double r) : start(a), end(b) {
        radius_squared = make_capsule_query(a, b, r).radius_squared;
        radius = r;
        node_radius = r + kPlaneSlack * (1.0 + std::max(max_abs(a), max_abs(b)) + r);
    }

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

    /// The ellipsoid scaled about its center by 1 + margin / (smallest semi-axis). Throws
    /// trackphys::Error on a non-finite end or a bad margin.
    EllipsoidShape(const Ellipsoid& e, const glm::dvec3& end_center, double margin)
        : start(e.center()), end(end_center) {
        if (!is_finite(end_center))
            throw Error("plane tree swept-ellipsoid query: end center is not finite");
        if (!std::isfinite(margin) || !(margin >= 0.0))
            throw Error("plane tree swept-ellipsoid query: margin must be finite and >= 0, got " +
                        std::to_string(margin));
        const glm::dvec3 radii = e.sorted_radii() * (1.0 + margin / e.sorted_radii().z);
        const glm::dmat3& q = e.sorted_axes();
        glm::dmat3 d2(0.0), d_inv(0.0);
        for (int k = 0; k < 3; ++k) {
            d2[k][k] = radii[k] * radii[k];
            d_inv[k][k] = 1.0 / radii[k];
        }
        const glm::dmat3 m = q * d2 * glm::transpose(q);
        m00 = m[0][0], m11 = m[1][1], m22 = m[2][2], m01 = m[0][1], m02 = m[0][2], m12 = m[1][2];
        to_unit = d_inv * glm::transpose(q);
        unit_end = to_unit * (end - start);
        // Rounding in the unit-ball frame is relative to that frame's coordinates, which
        // stretch world lengths by up to 1 / (smallest radius): the slack scales with it.
        slack = kPlaneSlack * (1.0 + std::max(max_abs(start), max_abs(end)) + radii.x) *
                (radii.x / radii.z);
    }

    double support(const glm::dvec3& u) const {
        return std::sqrt(m00 * u.x * u.x + m11 * u.y * u.y + m22 * u.z * u.z +
                         2.0 * (m01 * u.x * u.y + m02 * u.x * u.z + m12 * u.y * u.z));
    }

    bool reaches(const PlaneTreeNode& node) const {
        const glm::dvec3 n = node_normal(node);
        const double low = std::min(glm::dot(n, start), glm::dot(n, end));
        return low - support(n) - slack <= double(node.offset);
    }

    bool reaches_slab(const PlaneTreeSlab& slab) const {
        const glm::dvec3 n(slab.normal[0], slab.normal[1], slab.normal[2]);
        const double a = glm::dot(n, start), b = glm::dot(n, end);
        return meets_slab(std::min(a, b), std::max(a, b), support(n) + slack, slab);
    }

    bool touches(const NormalizedTriangle& t) const {
        const glm::dvec3 a = to_local(t, start), b = to_local(t, end);
        const glm::dvec3 lo = glm::min(a, b), hi = glm::max(a, b);
        if (misses(lo.z, hi.z, support(t.normal), 0.0) ||
            misses(lo.x, hi.x, support(t.dir_x), t.x1) ||
            misses(lo.y, hi.y, support(t.dir_y), t.y2))
            return false;
        return segment_within(glm::dvec3(0.0), unit_end, to_unit * (t.vertex(0) - start),
                              to_unit * (t.vertex(1) - start), to_unit * (t.vertex(2) - start),
                              1.0);
    }
};

}  // namespace trackphys::collision_detail
