#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

#include "trackphys/geometry/ellipsoid.hpp"
#include "trackphys/geometry/normalized_triangle.hpp"

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

/// ellipsoid_depth_bound for one ellipsoid on two triangles at once, bit for bit: each lane
/// of a two-double vector runs the scalar function's IEEE operations in its order (the
/// build contracts no multiply-add, see cmake/CompilerOptions.cmake), so only the count of
/// instructions changes. The ellipsoid's centre, axes and radii are spread into both lanes
/// once, when the cull is made; the triangles' frames at each test.
class EllipsoidCull {
  public:
    explicit EllipsoidCull(const Ellipsoid& e) {
        const glm::dmat3& axes = e.sorted_axes();
        for (int j = 0; j < 3; ++j) {
            center_[j] = both(e.center()[j]);
            radii_[j] = both(e.sorted_radii()[j]);
            axes_[j] = spread(axes[j], axes[j]);
        }
    }

    /// {ellipsoid_depth_bound(t, e), ellipsoid_depth_bound(u, e)}.
    std::array<double, 2> depth_bounds(const NormalizedTriangle& t,
                                       const NormalizedTriangle& u) const {
        const Lanes3 local{center_[0] - Lanes{t.origin.x, u.origin.x},
                           center_[1] - Lanes{t.origin.y, u.origin.y},
                           center_[2] - Lanes{t.origin.z, u.origin.z}};
        const Lanes3 normal = spread(t.normal, u.normal);
        const Lanes3 dir_x = spread(t.dir_x, u.dir_x);
        const Lanes3 dir_y = spread(t.dir_y, u.dir_y);
        const Lanes z = dot(normal, local);
        const Lanes x = dot(dir_x, local);
        const Lanes y = dot(dir_y, local);
        const Lanes hz = extent(normal);
        const Lanes hx = extent(dir_x);
        const Lanes hy = extent(dir_y);
        const Lanes x1{t.x1, u.x1};
        const Lanes y2{t.y2, u.y2};
        const auto apart =
            (z > hz) | (z < -hz) | (x < -hx) | (x > x1 + hx) | (y < -hy) | (y > y2 + hy);
        constexpr double kApart = -std::numeric_limits<double>::infinity();
        return {apart[0] ? kApart : hz[0] - std::abs(z[0]),
                apart[1] ? kApart : hz[1] - std::abs(z[1])};
    }

  private:
    using Lanes = double __attribute__((vector_size(16)));
    struct Lanes3 {
        Lanes x, y, z;
    };

    static Lanes both(double v) { return Lanes{v, v}; }
    static Lanes3 spread(const glm::dvec3& p, const glm::dvec3& q) {
        return {Lanes{p.x, q.x}, Lanes{p.y, q.y}, Lanes{p.z, q.z}};
    }
    // glm::dot's order: (x + y) + z.
    static Lanes dot(const Lanes3& u, const Lanes3& v) { return u.x * v.x + u.y * v.y + u.z * v.z; }
    // support_extent's: D (u A), each component in glm's order, then its length.
    Lanes extent(const Lanes3& u) const {
        const Lanes s0 = radii_[0] * dot(axes_[0], u);
        const Lanes s1 = radii_[1] * dot(axes_[1], u);
        const Lanes s2 = radii_[2] * dot(axes_[2], u);
        const Lanes squared = s0 * s0 + s1 * s1 + s2 * s2;
        return Lanes{std::sqrt(squared[0]), std::sqrt(squared[1])};
    }

    Lanes center_[3];
    Lanes radii_[3];
    Lanes3 axes_[3];  // the sorted axes, column j in axes_[j]
};

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
