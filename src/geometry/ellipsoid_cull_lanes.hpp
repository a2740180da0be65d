#pragma once

#include <array>
#include <limits>

#include "geometry/lane_ops.hpp"
#include "trackphys/geometry/ellipsoid.hpp"
#include "trackphys/geometry/normalized_triangle.hpp"

namespace trackphys::detail {

/// ellipsoid_depth_bound for one ellipsoid on N triangles at once (N = 2 or 4), bit for
/// bit: each lane of an N-double vector runs the scalar function's IEEE operations in its
/// order (the build contracts no multiply-add, see cmake/CompilerOptions.cmake), so only
/// the count of instructions changes. The ellipsoid's centre, axes and radii are spread
/// into every lane once, when the cull is made; the triangles' frames at each test. Every
/// member is forced inline, as LaneOps' are: four lanes run inside the AVX2 caller
/// (ellipsoid_cull_list.hpp).
template <int N>
class EllipsoidCull {
  public:
    [[gnu::always_inline]] explicit EllipsoidCull(const Ellipsoid& e) {
        const glm::dmat3& axes = e.sorted_axes();
        for (int j = 0; j < 3; ++j) {
            center_[j] = Ops::every(e.center()[j]);
            radii_[j] = Ops::every(e.sorted_radii()[j]);
            axes_[j] = {Ops::every(axes[j].x), Ops::every(axes[j].y), Ops::every(axes[j].z)};
        }
    }

    /// Lane k: ellipsoid_depth_bound(*t[k], e).
    [[gnu::always_inline]] std::array<double, N> depth_bounds(
        const NormalizedTriangle* const (&t)[N]) const {
        const typename Ops::Frames f = Ops::frames(t);
        const Lanes3 local{center_[0] - f.origin.x, center_[1] - f.origin.y,
                           center_[2] - f.origin.z};
        const Lanes z = Ops::dot(f.normal, local);
        const Lanes x = Ops::dot(f.dir_x, local);
        const Lanes y = Ops::dot(f.dir_y, local);
        const Lanes hz = extent(f.normal);
        const Lanes hx = extent(f.dir_x);
        const Lanes hy = extent(f.dir_y);
        const Mask apart =
            (z > hz) | (z < -hz) | (x < -hx) | (x > f.x1 + hx) | (y < -hy) | (y > f.y2 + hy);
        // hz - |z|, or -infinity where apart: |z| and the choice by bits, as fabs and the
        // scalar's ?: give them.
        return Ops::stored(Ops::select(apart, Ops::every(kApart), hz - Ops::abs(z)));
    }

  private:
    using Ops = LaneOps<N>;
    using Lanes = typename Ops::Lanes;
    using Mask = typename Ops::Mask;
    using Lanes3 = typename Ops::Lanes3;
    static constexpr double kApart = -std::numeric_limits<double>::infinity();

    // support_extent's: D (u A), each component in glm's order, then its length.
    [[gnu::always_inline]] Lanes extent(const Lanes3& u) const {
        const Lanes s0 = radii_[0] * Ops::dot(axes_[0], u);
        const Lanes s1 = radii_[1] * Ops::dot(axes_[1], u);
        const Lanes s2 = radii_[2] * Ops::dot(axes_[2], u);
        return Ops::sqrt(s0 * s0 + s1 * s1 + s2 * s2);
    }

    Lanes center_[3];
    Lanes radii_[3];
    Lanes3 axes_[3];  // the sorted axes, column j in axes_[j]
};

}  // namespace trackphys::detail
