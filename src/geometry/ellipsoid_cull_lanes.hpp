#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
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
/// Every member is forced inline, and calls nothing that is not a built-in (memcpy and the
/// vector extensions' shuffles are): four lanes are
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

    /// Lane k: ellipsoid_depth_bound(*t[k], e).
    [[gnu::always_inline]] std::array<double, N> depth_bounds(
        const NormalizedTriangle* const (&t)[N]) const {
        const Frames f = gather(t);
        const Lanes3 local{center_[0] - f.origin.x, center_[1] - f.origin.y,
                           center_[2] - f.origin.z};
        const Lanes z = dot(f.normal, local);
        const Lanes x = dot(f.dir_x, local);
        const Lanes y = dot(f.dir_y, local);
        const Lanes hz = extent(f.normal);
        const Lanes hx = extent(f.dir_x);
        const Lanes hy = extent(f.dir_y);
        const Mask apart =
            (z > hz) | (z < -hz) | (x < -hx) | (x > f.x1 + hx) | (y < -hy) | (y > f.y2 + hy);
        // hz - |z|, or -infinity where apart: |z| and the choice by bits, as fabs and the
        // scalar's ?: give them.
        const Mask depth = to_bits(hz - from_bits(to_bits(z) & ~kSign));
        const Lanes bounds = from_bits((depth & ~apart) | (to_bits(every(kApart)) & apart));
        // Stored as it is, by memcpy (a bit_cast took a detour through the stack).
        std::array<double, N> out;
        std::memcpy(out.data(), &bounds, sizeof bounds);
        return out;
    }

  private:
    using Lanes = typename DoubleLanes<N>::type;
    using Mask = decltype(Lanes{} < Lanes{});  // all ones in a lane where it holds
    struct Lanes3 {
        Lanes x, y, z;
    };
    struct Frames {
        Lanes3 origin, dir_x, dir_y, normal;
        Lanes x1, y2;
    };
    struct Columns4 {
        Lanes c0, c1, c2, c3;
    };
    static constexpr double kApart = -std::numeric_limits<double>::infinity();
    static constexpr std::int64_t kSign = std::numeric_limits<std::int64_t>::min();  // bit 63

    // v in lane 0, shuffled to every lane: one broadcast from v's place in memory.
    [[gnu::always_inline]] static Lanes every(double v) {
        const Lanes first{v};
        if constexpr (N == 2)
            return __builtin_shufflevector(first, first, 0, 0);
        else
            return __builtin_shufflevector(first, first, 0, 0, 0, 0);
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
    // Doubles i to i + 3 of a frame (its layout is checked in gather), by memcpy: a frame is
    // 8-byte aligned, and clang loads through an under-aligned vector type as if aligned.
    [[gnu::always_inline]] static Lanes row(const NormalizedTriangle* t, std::size_t i) {
        Lanes r;
        std::memcpy(&r, reinterpret_cast<const char*>(t) + i * sizeof(double), sizeof r);
        return r;
    }
    // Doubles i to i + 3 of the four frames, transposed: column c holds each frame's double
    // i + c, from four 32-byte loads and eight shuffles.
    [[gnu::always_inline]] static Columns4 transposed(const NormalizedTriangle* const (&t)[4],
                                                      std::size_t i) {
        const Lanes r0 = row(t[0], i), r1 = row(t[1], i), r2 = row(t[2], i), r3 = row(t[3], i);
        const Lanes even01 = __builtin_shufflevector(r0, r1, 0, 4, 2, 6);
        const Lanes odd01 = __builtin_shufflevector(r0, r1, 1, 5, 3, 7);
        const Lanes even23 = __builtin_shufflevector(r2, r3, 0, 4, 2, 6);
        const Lanes odd23 = __builtin_shufflevector(r2, r3, 1, 5, 3, 7);
        return {__builtin_shufflevector(even01, even23, 0, 1, 4, 5),
                __builtin_shufflevector(odd01, odd23, 0, 1, 4, 5),
                __builtin_shufflevector(even01, even23, 2, 3, 6, 7),
                __builtin_shufflevector(odd01, odd23, 2, 3, 6, 7)};
    }
    // The frames' values the bound reads, frame k in lane k. Four lanes read each frame as
    // the 15 doubles it is laid out as, in rows of four (the last row, doubles 11-14, ends at
    // the frame's end); two lanes a value at a time, a load and a load-high each.
    [[gnu::always_inline]] static Frames gather(const NormalizedTriangle* const (&t)[N]) {
        if constexpr (N == 4) {
            using F = NormalizedTriangle;
            constexpr std::size_t d = sizeof(double);
            static_assert(sizeof(F) == 15 * d && offsetof(F, origin) == 0 &&
                          offsetof(F, dir_x) == 3 * d && offsetof(F, dir_y) == 6 * d &&
                          offsetof(F, normal) == 9 * d && offsetof(F, x1) == 12 * d &&
                          offsetof(F, y2) == 14 * d);
            const Columns4 a = transposed(t, 0);
            const Columns4 b = transposed(t, 4);
            const Columns4 c = transposed(t, 8);
            const Columns4 d11 = transposed(t, 11);
            return {{a.c0, a.c1, a.c2},
                    {a.c3, b.c0, b.c1},
                    {b.c2, b.c3, c.c0},
                    {c.c1, c.c2, c.c3},
                    d11.c1,
                    d11.c3};
        } else {
            return {gather(t, &NormalizedTriangle::origin), gather(t, &NormalizedTriangle::dir_x),
                    gather(t, &NormalizedTriangle::dir_y),  gather(t, &NormalizedTriangle::normal),
                    gather(t, &NormalizedTriangle::x1),     gather(t, &NormalizedTriangle::y2)};
        }
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
