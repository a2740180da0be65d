#pragma once

// EllipsoidShape::touches on N kept frames at once (private): the plane tree's filter of a
// swept ellipsoid query, in the lanes of an N-double vector (N = 4 under AVX2, else 2).

#include <algorithm>

#include "collision/plane_tree_shapes.hpp"
#include "geometry/lane_ops.hpp"
#include "trackphys/geometry/normalized_triangle.hpp"

namespace trackphys::collision_detail {

/// EllipsoidShape::touches's bounds for N frames at once, bit for bit: each lane runs the
/// scalar filter's IEEE operations in its order (the build contracts no multiply-add), so
/// every lane decides as the scalar filter does. The scalar filter stops at the first test
/// that decides; the lanes run every test and take, lane by lane, the first one's answer:
/// the plane and local box reject, the sure accept accepts, the slanted edges and tilted
/// axes reject, and the exact test (scalar, EllipsoidShape::touches_exactly) gets the rest.
///
/// Every member is forced inline and calls nothing that is not a built-in: four lanes are
/// 32-byte vectors, which only code compiled for AVX holds in one register, so they run
/// inside the AVX2 caller (plane_tree.cpp) and never as functions of the library's own
/// x86-64 level.
template <int N>
class EllipsoidFilterLanes {
  public:
    /// What the bounds decide for the N frames: bit k of `touched` when frame k surely
    /// touches, of `undecided` when only the exact test can tell.
    struct Decisions {
        unsigned touched = 0, undecided = 0;
    };

    [[gnu::always_inline]] explicit EllipsoidFilterLanes(const EllipsoidShape& shape) {
        for (int j = 0; j < 3; ++j) {
            start_[j] = Ops::every(shape.start[j]);
            end_[j] = Ops::every(shape.end[j]);
        }
        m00_ = Ops::every(shape.m00);
        m11_ = Ops::every(shape.m11);
        m22_ = Ops::every(shape.m22);
        m01_ = Ops::every(shape.m01);
        m02_ = Ops::every(shape.m02);
        m12_ = Ops::every(shape.m12);
        reach_squared_ = Ops::every(shape.reach_squared);
    }

    [[gnu::always_inline]] Decisions decide(const NormalizedTriangle* const (&t)[N]) const {
        const Lanes3 origin = Ops::gather(t, &NormalizedTriangle::origin);
        const Lanes3 from_a{start_[0] - origin.x, start_[1] - origin.y, start_[2] - origin.z};
        const Lanes3 from_b{end_[0] - origin.x, end_[1] - origin.y, end_[2] - origin.z};
        // The plane and the local box.
        const Lanes3 normal = Ops::gather(t, &NormalizedTriangle::normal);
        const Lanes az = Ops::dot(normal, from_a), bz = Ops::dot(normal, from_b);
        const Lanes z_lo = min(az, bz), z_hi = max(az, bz);
        const Lanes z_gap = max3(z_lo, -z_hi, Ops::every(0.0));
        const Lanes h_sq = support_squared(normal);
        Mask rejected = (z_gap > 0.0) & (z_gap * z_gap > h_sq);
        const Lanes3 dir_x = Ops::gather(t, &NormalizedTriangle::dir_x);
        const Lanes ax = Ops::dot(dir_x, from_a), bx = Ops::dot(dir_x, from_b);
        const Lanes x1 = Ops::gather(t, &NormalizedTriangle::x1);
        const Lanes x_gap = max3(min(ax, bx) - x1, -max(ax, bx), Ops::every(0.0));
        rejected |= (x_gap > 0.0) &
                    ((x_gap * x_gap > reach_squared_) | (x_gap * x_gap > support_squared(dir_x)));
        const Lanes3 dir_y = Ops::gather(t, &NormalizedTriangle::dir_y);
        const Lanes ay = Ops::dot(dir_y, from_a), by = Ops::dot(dir_y, from_b);
        const Lanes y2 = Ops::gather(t, &NormalizedTriangle::y2);
        const Lanes y_gap = max3(min(ay, by) - y2, -max(ay, by), Ops::every(0.0));
        rejected |= (y_gap > 0.0) &
                    ((y_gap * y_gap > reach_squared_) | (y_gap * y_gap > support_squared(dir_y)));
        // Each stage runs only while a lane is left open by the ones before.
        const unsigned open = Ops::bits(~rejected);
        if (open == 0) return {};
        // The sure accept: the chord's foot over the triangle for some t in [0, 1].
        const Lanes x2 = Ops::gather(t, &NormalizedTriangle::x2);
        const Lanes ex = x2 - x1;
        const Lanes h = Ops::sqrt(h_sq);
        const Lanes3 mn{m00_ * normal.x + m01_ * normal.y + m02_ * normal.z,
                        m01_ * normal.x + m11_ * normal.y + m12_ * normal.z,
                        m02_ * normal.x + m12_ * normal.y + m22_ * normal.z};
        const Lanes mn_x = Ops::dot(dir_x, mn) / h_sq, mn_y = Ops::dot(dir_y, mn) / h_sq;
        const Lanes xa = ax - az * mn_x, ya = ay - az * mn_y;
        const Lanes xb = bx - bz * mn_x, yb = by - bz * mn_y;
        Interval kept{Ops::every(0.0), Ops::every(1.0)};
        kept.keep_below(az - h, bz - h);
        kept.keep_below(-az - h, -bz - h);
        kept.keep_below(-ya, -yb);
        kept.keep_below(x2 * ya - y2 * xa, x2 * yb - y2 * xb);
        kept.keep_below((xa - x1) * y2 - ya * ex, (xb - x1) * y2 - yb * ex);
        const unsigned touched = open & Ops::bits(kept.first <= kept.last);
        if (touched == open) return {touched, 0};
        // The slanted edges' half-planes.
        const Lanes e1 = min(x2 * ay - y2 * ax, x2 * by - y2 * bx);
        const Lanes e2 = min((ax - x1) * y2 - ay * ex, (bx - x1) * y2 - by * ex);
        Mask separated = ((e1 > 0.0) & (e1 * e1 > support_squared(x2 * dir_y - y2 * dir_x))) |
                         ((e2 > 0.0) & (e2 * e2 > support_squared(y2 * dir_x - ex * dir_y)));
        // The tilted separating axes, for a shape on one side of the plane.
        const Lanes side = Ops::select(z_lo > 0.0, Ops::every(1.0), Ops::every(-1.0));
        const Lanes3 a{ax, ay, az}, b{bx, by, bz};
        const Lanes zero = Ops::every(0.0);
        separated |=
            ((z_lo > 0.0) | (z_hi < 0.0)) &
            (tilted_apart(a, b, dir_x, dir_y, normal, zero, -x1, zero, side * x1) |
             tilted_apart(a, b, dir_x, dir_y, normal, -y2, x2, zero, side * (Ops::abs(x2) + y2)) |
             tilted_apart(a, b, dir_x, dir_y, normal, y2, -ex, x1 * y2,
                          side * (Ops::abs(ex) + y2)));
        return {touched, open & ~touched & Ops::bits(~separated)};
    }

  private:
    using Ops = detail::LaneOps<N>;
    using Lanes = typename Ops::Lanes;
    using Mask = typename Ops::Mask;
    using Lanes3 = typename Ops::Lanes3;

    // The t in [first, last] kept so far by EllipsoidShape::touches's keep_below.
    struct Interval {
        Lanes first, last;
        // keep_below's branches, lane by lane: both ends above (nothing is kept), the
        // start above (first rises), the end above (last falls), or neither (no change).
        [[gnu::always_inline]] void keep_below(const Lanes& fa, const Lanes& fb) {
            const Mask neither = (fa <= 0.0) & (fb <= 0.0);
            const Mask both = (fa > 0.0) & (fb > 0.0);
            const Mask start = ~neither & ~both & (fa > 0.0);
            const Mask end = ~neither & ~both & ~(fa > 0.0);
            const Lanes crossing = fa / (fa - fb);
            first =
                Ops::select(both, Ops::every(2.0), Ops::select(start, max(first, crossing), first));
            last = Ops::select(end, min(last, crossing), last);
        }
    };

    // std::min and std::max's choices: the second only when it compares below (above) the
    // first, and std::max({a, b, c})'s first largest.
    [[gnu::always_inline]] static Lanes min(const Lanes& a, const Lanes& b) {
        return Ops::select(b < a, b, a);
    }
    [[gnu::always_inline]] static Lanes max(const Lanes& a, const Lanes& b) {
        return Ops::select(a < b, b, a);
    }
    [[gnu::always_inline]] static Lanes max3(const Lanes& a, const Lanes& b, const Lanes& c) {
        return max(max(a, b), c);
    }
    // touches's `separated`: the sweep's ends a and b beyond the tilted axis
    // d = ux dir_x + uy dir_y + sl normal by more than the ellipsoid reaches along it.
    [[gnu::always_inline]] Mask tilted_apart(const Lanes3& a, const Lanes3& b, const Lanes3& dir_x,
                                             const Lanes3& dir_y, const Lanes3& normal,
                                             const Lanes& ux, const Lanes& uy, const Lanes& offset,
                                             const Lanes& sl) const {
        const Lanes m =
            min(ux * a.x + uy * a.y + sl * a.z, ux * b.x + uy * b.y + sl * b.z) - offset;
        return (m > 0.0) & (m * m > support_squared(ux * dir_x + uy * dir_y + sl * normal));
    }
    // EllipsoidShape::support_squared's order.
    [[gnu::always_inline]] Lanes support_squared(const Lanes3& u) const {
        return m00_ * u.x * u.x + m11_ * u.y * u.y + m22_ * u.z * u.z +
               2.0 * (m01_ * u.x * u.y + m02_ * u.x * u.z + m12_ * u.y * u.z);
    }

    Lanes start_[3], end_[3];
    Lanes m00_, m11_, m22_, m01_, m02_, m12_;
    Lanes reach_squared_;
};

}  // namespace trackphys::collision_detail
