#pragma once

// The per-triangle predicates every StaticCollider query and its BruteForceCollider twin
// share. Both call exactly these functions on exactly the same double vertices, so they
// agree bit for bit; the BVH is exact because each predicate starts with a test that is
// monotone in the box (a larger box never fails where a smaller one passes, rounding
// included), and a node's box holds each of its triangles' boxes.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <vector>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "trackphys/collision/static_collider.hpp"
#include "trackphys/geometry/aabb.hpp"
#include "trackphys/geometry/triangle_mesh.hpp"

namespace trackphys::collision_detail {

inline Aabb triangle_box(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
    return {glm::min(a, glm::min(b, c)), glm::max(a, glm::max(b, c))};
}

// --- distances (double; callers compare squared distances with radius^2) ---------------

inline double point_segment_distance_squared(const glm::dvec3& p, const glm::dvec3& a,
                                             const glm::dvec3& b) {
    const glm::dvec3 ab = b - a;
    const double length_squared = glm::dot(ab, ab);
    const double t =
        length_squared > 0.0 ? std::clamp(glm::dot(p - a, ab) / length_squared, 0.0, 1.0) : 0.0;
    const glm::dvec3 d = p - (a + ab * t);
    return glm::dot(d, d);
}

// True when x projects onto the triangle (a, b, c) with area normal n: it lies on the
// inner side of all three edges (closed).
inline bool projects_inside(const glm::dvec3& x, const glm::dvec3& a, const glm::dvec3& b,
                            const glm::dvec3& c, const glm::dvec3& n) {
    return glm::dot(glm::cross(b - a, x - a), n) >= 0.0 &&
           glm::dot(glm::cross(c - b, x - b), n) >= 0.0 &&
           glm::dot(glm::cross(a - c, x - c), n) >= 0.0;
}

/// Squared distance from p to the triangle: the plane distance when p projects inside,
/// else the distance to the nearest edge (the closest point is then on the boundary).
inline double point_triangle_distance_squared(const glm::dvec3& p, const glm::dvec3& a,
                                              const glm::dvec3& b, const glm::dvec3& c) {
    const glm::dvec3 n = glm::cross(b - a, c - a);
    if (projects_inside(p, a, b, c, n)) {
        const double h = glm::dot(p - a, n);
        return h * h / glm::dot(n, n);
    }
    return std::min({point_segment_distance_squared(p, a, b),
                     point_segment_distance_squared(p, b, c),
                     point_segment_distance_squared(p, c, a)});
}

/// Squared distance between segments [p0, p1] and [q0, q1] (Ericson, "Real-Time Collision
/// Detection", 5.1.9): minimise over s for the unclamped t, then clamp t and re-solve s.
/// Every branch ends at a pair of points on the two segments, so near-parallel rounding
/// can only cost accuracy in the last bits, never return a point off a segment.
inline double segment_segment_distance_squared(const glm::dvec3& p0, const glm::dvec3& p1,
                                               const glm::dvec3& q0, const glm::dvec3& q1) {
    const glm::dvec3 d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
    const double a = glm::dot(d1, d1), e = glm::dot(d2, d2), f = glm::dot(d2, r);
    double s = 0.0, t = 0.0;
    if (a == 0.0 && e == 0.0) {
        // both are points
    } else if (a == 0.0) {
        t = std::clamp(f / e, 0.0, 1.0);
    } else {
        const double c = glm::dot(d1, r);
        if (e == 0.0) {
            s = std::clamp(-c / a, 0.0, 1.0);
        } else {
            const double b = glm::dot(d1, d2);
            const double denominator = a * e - b * b;  // >= 0, zero when parallel
            s = denominator > 0.0 ? std::clamp((b * f - c * e) / denominator, 0.0, 1.0) : 0.0;
            t = (b * s + f) / e;
            if (t < 0.0) {
                t = 0.0;
                s = std::clamp(-c / a, 0.0, 1.0);
            } else if (t > 1.0) {
                t = 1.0;
                s = std::clamp((b - c) / a, 0.0, 1.0);
            }
        }
    }
    const glm::dvec3 d = (p0 + d1 * s) - (q0 + d2 * t);
    return glm::dot(d, d);
}

/// Squared distance from segment [s0, s1] to the triangle: 0 when the segment crosses it,
/// else the least of the endpoints' distances and the segment's distances to the three edges
/// (a closest pair with both points interior would make the segment parallel to the plane,
/// and then an endpoint is as close).
inline double segment_triangle_distance_squared(const glm::dvec3& s0, const glm::dvec3& s1,
                                                const glm::dvec3& a, const glm::dvec3& b,
                                                const glm::dvec3& c) {
    const glm::dvec3 n = glm::cross(b - a, c - a);
    const double h0 = glm::dot(s0 - a, n), h1 = glm::dot(s1 - a, n);
    if (((h0 <= 0.0 && h1 >= 0.0) || (h0 >= 0.0 && h1 <= 0.0)) && h0 != h1) {
        const glm::dvec3 crossing = s0 + (s1 - s0) * (h0 / (h0 - h1));
        if (projects_inside(crossing, a, b, c, n)) return 0.0;
    }
    return std::min({point_triangle_distance_squared(s0, a, b, c),
                     point_triangle_distance_squared(s1, a, b, c),
                     segment_segment_distance_squared(s0, s1, a, b),
                     segment_segment_distance_squared(s0, s1, b, c),
                     segment_segment_distance_squared(s0, s1, c, a)});
}

// --- sphere and capsule queries ---------------------------------------------------------

/// A sphere (segment length 0) or capsule query: the shape, its box, radius^2.
struct CapsuleQuery {
    glm::dvec3 start, end;
    double radius_squared;
    Aabb box;
};

/// Validates and prepares a capsule query; throws trackphys::Error on bad input.
CapsuleQuery make_capsule_query(const glm::dvec3& start, const glm::dvec3& end, double radius);

inline bool sphere_keeps(const CapsuleQuery& q, const glm::dvec3& a, const glm::dvec3& b,
                         const glm::dvec3& c) {
    return triangle_box(a, b, c).overlaps(q.box) &&
           point_triangle_distance_squared(q.start, a, b, c) <= q.radius_squared;
}

inline bool capsule_keeps(const CapsuleQuery& q, const glm::dvec3& a, const glm::dvec3& b,
                          const glm::dvec3& c) {
    return triangle_box(a, b, c).overlaps(q.box) &&
           segment_triangle_distance_squared(q.start, q.end, a, b, c) <= q.radius_squared;
}

// --- ray cast ----------------------------------------------------------------------------

/// A prepared ray. inv_dir is 1/dir, and +infinity for a zero component of either sign,
/// so that ray_box_span sees one sign convention for rays lying in a slab's plane.
struct RayQuery {
    glm::dvec3 origin, dir, inv_dir;
    double max_distance;
};

/// Validates and prepares a ray; throws trackphys::Error on bad input.
RayQuery make_ray_query(const glm::dvec3& origin, const glm::dvec3& unit_dir, double max_distance);

/// The ray's parameter span through the box [lo, hi], limited to [0, t_limit]; false when
/// empty. Slab test with Ize's robust factor ("Robust BVH Ray Traversal", 2013) so that
/// rounding never loses a box the exact ray touches. A zero direction component gives
/// t0 <= t1 in {-inf, NaN, +inf} (inv_dir = +inf): NaN (origin on the slab's plane) fails
/// every comparison and so constrains nothing, which keeps the closed-box meaning.
/// Monotone: a larger box gives a span that contains the smaller box's span.
inline bool ray_box_span(const RayQuery& ray, const glm::dvec3& lo, const glm::dvec3& hi,
                         double t_limit, double& t_near, double& t_far) {
    constexpr double kGamma3 = 3.0 * 0x1p-53 / (1.0 - 3.0 * 0x1p-53);
    constexpr double kFarScale = 1.0 + 2.0 * kGamma3;
    t_near = 0.0;
    t_far = t_limit;
    for (int axis = 0; axis < 3; ++axis) {
        double t0 = (lo[axis] - ray.origin[axis]) * ray.inv_dir[axis];
        double t1 = (hi[axis] - ray.origin[axis]) * ray.inv_dir[axis];
        if (t0 > t1) std::swap(t0, t1);
        t1 *= kFarScale;
        t_near = t0 > t_near ? t0 : t_near;
        t_far = t1 < t_far ? t1 : t_far;
    }
    return t_near <= t_far;
}

/// A box around the ray's points for t in [t0, t1] (0 <= t0 <= t1), padded by 2e-9 of the
/// scale (|origin| + t1) and by 1e-300: nullopt when t1 or a bound is not finite. Every
/// triangle that ray_triangle hits at a t in [t0, t1] has its box overlapping it: the hit
/// point lies within the triangle's box but for ray_box_span's robust slack and the
/// rounding of the points, both within about 1e-15 of the scale (so a box query can cull
/// a leaf's slots before their slab tests).
inline std::optional<Aabb> ray_segment_box(const RayQuery& ray, double t0, double t1) {
    if (!(t1 < std::numeric_limits<double>::infinity())) return {};
    const glm::dvec3 p0 = ray.origin + ray.dir * t0, p1 = ray.origin + ray.dir * t1;
    const glm::dvec3 a = glm::abs(ray.origin);
    const double pad = 2e-9 * (std::max({a.x, a.y, a.z}) + t1) + 1e-300;
    const Aabb box{glm::min(p0, p1) - pad, glm::max(p0, p1) + pad};
    for (int axis = 0; axis < 3; ++axis)
        if (!(std::abs(box.min[axis]) < std::numeric_limits<double>::infinity() &&
              std::abs(box.max[axis]) < std::numeric_limits<double>::infinity()))
            return {};
    return box;
}

/// Two-sided Moller-Trumbore hit distance in [0, max_distance], or nullopt. The distance is
/// clamped into the ray's (unlimited) span through the triangle's box, so that it never
/// lies before a node's entry distance (what makes closest-hit pruning exact) and does not
/// depend on max_distance. A crossing behind the origin (t < 0) is a miss.
inline std::optional<double> ray_triangle(const RayQuery& ray, const glm::dvec3& a,
                                          const glm::dvec3& b, const glm::dvec3& c) {
    const Aabb box = triangle_box(a, b, c);
    double t_near, t_far;
    if (!ray_box_span(ray, box.min, box.max, std::numeric_limits<double>::infinity(), t_near,
                      t_far) ||
        t_near > ray.max_distance)
        return {};
    const glm::dvec3 e1 = b - a, e2 = c - a;
    const glm::dvec3 p = glm::cross(ray.dir, e2);
    const double det = glm::dot(e1, p);
    if (det == 0.0) return {};
    const double inv_det = 1.0 / det;
    const glm::dvec3 s = ray.origin - a;
    const double u = glm::dot(s, p) * inv_det;
    if (!(u >= 0.0 && u <= 1.0)) return {};
    const glm::dvec3 q = glm::cross(s, e1);
    const double v = glm::dot(ray.dir, q) * inv_det;
    if (!(v >= 0.0 && u + v <= 1.0)) return {};
    double t = glm::dot(e2, q) * inv_det;
    // Two-sided means either face, not either way along the line: t < 0 is the line
    // crossing the triangle behind the origin. The clamp below only absorbs rounding (a t
    // a few ulps outside the box span that the crossing point lies in); a negative t is no
    // rounding error, and clamped it would be the span's start, a hit at 0 whenever the
    // origin lies in the triangle's box (a point above a long, steep kerb triangle). NaN
    // (0 * infinity from a det near the smallest double) still goes to the clamp.
    if (t < 0.0) return {};
    t = t > t_near ? t : t_near;  // also maps NaN to t_near
    t = t < t_far ? t : t_far;
    if (t > ray.max_distance) return {};
    return t;
}

/// The closest-hit order: smaller distance, then the lower mesh index.
inline bool better_hit(double t, std::uint32_t triangle, double best_t,
                       std::uint32_t best_triangle) {
    return t < best_t || (t == best_t && triangle < best_triangle);
}

inline glm::dvec3 unit_normal(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
    return glm::normalize(glm::cross(b - a, c - a));
}

/// Validates the mesh: throws trackphys::Error naming the first bad vertex or triangle.
/// Returns, in mesh order, the indices of the non-degenerate triangles.
std::vector<std::uint32_t> validate_and_keep(const TriangleMesh& mesh);

}  // namespace trackphys::collision_detail
