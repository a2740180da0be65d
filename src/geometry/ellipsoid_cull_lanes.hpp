#pragma once

#include <array>
#include <cmath>
#include <limits>

#include "trackphys/geometry/ellipsoid.hpp"
#include "trackphys/geometry/normalized_triangle.hpp"

namespace trackphys::detail {

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

}  // namespace trackphys::detail
