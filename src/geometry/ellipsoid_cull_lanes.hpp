#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>

#include "trackphys/geometry/ellipsoid.hpp"
#include "trackphys/geometry/normalized_triangle.hpp"

namespace trackphys::detail {

// N doubles in one vector (GCC takes no vector_size that depends on a template's argument).
template <int N>
struct DoubleLanes {};
template <>
struct DoubleLanes<2> {
    using type = double __attribute__((vector_size(16)));
};
template <>
struct DoubleLanes<4> {
    using type = double __attribute__((vector_size(32)));
};

// No member of EllipsoidCull exists out of line, so none passes a vector by the ABI GCC warns
// about for four lanes without AVX; GCC warns at the end of the including file, so the
// warning stays off there (this header is private: the world's cull and its test). Being
// off, it would not report a call that does pass one (std::bit_cast, a function, is one at
// -O0; __builtin_bit_cast is not): the cull's test is built at -O0 to catch that instead.
#pragma GCC diagnostic ignored "-Wpsabi"

/// ellipsoid_depth_bound for one ellipsoid on N triangles at once (N = 2 or 4), bit for
/// bit: each lane of an N-double vector runs the scalar function's IEEE operations in its
/// order (the build contracts no multiply-add, see cmake/CompilerOptions.cmake), so only
/// the count of instructions changes. The ellipsoid's centre, axes and radii are spread
/// into every lane once, when the cull is made; the triangles' frames at each test.
///
/// Every member is forced inline, and calls nothing that is not a built-in: four lanes are
/// 32-byte vectors, which only code compiled for AVX holds in one register, so they run
/// inside the AVX2 caller (ellipsoid_cull_list.hpp) and never as functions of the
/// library's own x86-64 level, at any optimisation level.
template <int N>
class EllipsoidCull {
  public:
    [[gnu::always_inline]] explicit EllipsoidCull(const Ellipsoid& e) {
        const glm::dmat3& axes = e.sorted_axes();
        for (int j = 0; j < 3; ++j) {
            center_[j] = every(e.center()[j]);
            radii_[j] = every(e.sorted_radii()[j]);
            axes_[j] = {every(axes[j].x), every(axes[j].y), every(axes[j].z)};
        }
    }

    /// The first N lanes of a wider cull of the same ellipsoid: a list's short tail goes
    /// into fewer lanes without spreading the ellipsoid again.
    template <int Wide>
    [[gnu::always_inline]] explicit EllipsoidCull(const EllipsoidCull<Wide>& wide) {
        static_assert(Wide == 2 * N);
        for (int j = 0; j < 3; ++j) {
            center_[j] = first_half(wide.center_[j]);
            radii_[j] = first_half(wide.radii_[j]);
            axes_[j] = {first_half(wide.axes_[j].x), first_half(wide.axes_[j].y),
                        first_half(wide.axes_[j].z)};
        }
    }

    /// Lane k: ellipsoid_depth_bound(*t[k], e).
    [[gnu::always_inline]] std::array<double, N> depth_bounds(
        const NormalizedTriangle* const (&t)[N]) const {
        const Lanes3 origin = gather(t, &NormalizedTriangle::origin);
        const Lanes3 local{center_[0] - origin.x, center_[1] - origin.y, center_[2] - origin.z};
        const Lanes3 normal = gather(t, &NormalizedTriangle::normal);
        const Lanes3 dir_x = gather(t, &NormalizedTriangle::dir_x);
        const Lanes3 dir_y = gather(t, &NormalizedTriangle::dir_y);
        const Lanes z = dot(normal, local);
        const Lanes x = dot(dir_x, local);
        const Lanes y = dot(dir_y, local);
        const Lanes hz = extent(normal);
        const Lanes hx = extent(dir_x);
        const Lanes hy = extent(dir_y);
        const Lanes x1 = gather(t, &NormalizedTriangle::x1);
        const Lanes y2 = gather(t, &NormalizedTriangle::y2);
        const Mask apart =
            (z > hz) | (z < -hz) | (x < -hx) | (x > x1 + hx) | (y < -hy) | (y > y2 + hy);
        // hz - |z|, or -infinity where apart: |z| and the choice by bits, as fabs and the
        // scalar's ?: give them.
        const Mask depth = to_bits(hz - from_bits(to_bits(z) & ~kSign));
        return __builtin_bit_cast(std::array<double, N>,
                                  (depth & ~apart) | (to_bits(every(kApart)) & apart));
    }

  private:
    using Lanes = typename DoubleLanes<N>::type;
    using Mask = decltype(Lanes{} < Lanes{});  // all ones in a lane where it holds
    struct Lanes3 {
        Lanes x, y, z;
    };
    static constexpr double kApart = -std::numeric_limits<double>::infinity();
    static constexpr std::int64_t kSign = std::numeric_limits<std::int64_t>::min();  // bit 63

    template <int>
    friend class EllipsoidCull;

    // v in lane 0, shuffled to every lane: GCC 12 makes that one vbroadcastsd from v's place in
    // memory, where filling the lanes one by one became a load, an unpack and a permute.
    [[gnu::always_inline]] static Lanes every(double v) {
        const Lanes first{v};
        if constexpr (N == 2)
            return __builtin_shufflevector(first, first, 0, 0);
        else
            return __builtin_shufflevector(first, first, 0, 0, 0, 0);
    }
    // A shuffle, not a copy lane by lane, so that the wide vector's low half is read as it is
    // (a copy kept the ellipsoid's scalars alive to spread them again).
    template <class WideLanes>
    [[gnu::always_inline]] static Lanes first_half(const WideLanes& v) {
        return __builtin_shufflevector(v, v, 0, 1);
    }
    [[gnu::always_inline]] static Mask to_bits(const Lanes& v) {
        return __builtin_bit_cast(Mask, v);
    }
    [[gnu::always_inline]] static Lanes from_bits(const Mask& m) {
        return __builtin_bit_cast(Lanes, m);
    }
    [[gnu::always_inline]] static Lanes gather(const NormalizedTriangle* const (&t)[N],
                                               double NormalizedTriangle::*field) {
        Lanes v{};
        for (int k = 0; k < N; ++k) v[k] = t[k]->*field;
        return v;
    }
    [[gnu::always_inline]] static Lanes3 gather(const NormalizedTriangle* const (&t)[N],
                                                glm::dvec3 NormalizedTriangle::*field) {
        Lanes3 v{};
        for (int k = 0; k < N; ++k) {
            const glm::dvec3& p = t[k]->*field;
            v.x[k] = p.x;
            v.y[k] = p.y;
            v.z[k] = p.z;
        }
        return v;
    }
    // glm::dot's order: (x + y) + z.
    [[gnu::always_inline]] static Lanes dot(const Lanes3& u, const Lanes3& v) {
        return u.x * v.x + u.y * v.y + u.z * v.z;
    }
    // support_extent's: D (u A), each component in glm's order, then its length.
    [[gnu::always_inline]] Lanes extent(const Lanes3& u) const {
        const Lanes s0 = radii_[0] * dot(axes_[0], u);
        const Lanes s1 = radii_[1] * dot(axes_[1], u);
        const Lanes s2 = radii_[2] * dot(axes_[2], u);
        const Lanes squared = s0 * s0 + s1 * s1 + s2 * s2;
        Lanes root{};
        for (int k = 0; k < N; ++k) root[k] = std::sqrt(squared[k]);
        return root;
    }

    Lanes center_[3];
    Lanes radii_[3];
    Lanes3 axes_[3];  // the sorted axes, column j in axes_[j]
};

}  // namespace trackphys::detail
