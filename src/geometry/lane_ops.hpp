#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>

#include <glm/vec3.hpp>

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

// No member here exists out of line, so none passes a vector by the ABI GCC warns about for
// four lanes without AVX; GCC warns at the end of the including file, so the warning stays
// off there (this header is private: the world's and the mid phase's lanes and their tests).
// Being off, it would not report a call that does pass one (std::bit_cast, a function, is
// one at -O0; __builtin_bit_cast is not): the lanes' tests are built at -O0 to catch that.
#pragma GCC diagnostic ignored "-Wpsabi"

/// What code that runs a scalar function in N lanes at once (N = 2 or 4) shares: the vector types,
/// spreading a value, reading triangles' frames into lanes, masks to bits, and the few operations
/// whose order must be the scalar code's (glm's dot, the square root). Each lane runs the scalar
/// IEEE operations in their order (the build contracts no multiply-add, see
/// cmake/CompilerOptions.cmake), so the lanes give the scalar bits.
///
/// Every member is forced inline, and calls nothing that is not a built-in (memcpy and the
/// vector extensions' shuffles are): four lanes are 32-byte vectors, which only code
/// compiled for AVX holds in one register, so they run inside an AVX2 caller and never as
/// functions of the library's own x86-64 level, at any optimisation level. The same holds for
/// code built on these: every function or lambda that takes or returns lanes is forced
/// inline, and its tests run it at -O0 too (a lambda is not inlined there on its own).
template <int N>
struct LaneOps {
    using Lanes = typename DoubleLanes<N>::type;
    using Mask = decltype(Lanes{} < Lanes{});  // all ones in a lane where it holds
    // Three coordinates in lanes, with glm's vector expressions: component by component.
    struct Lanes3 {
        Lanes x, y, z;

        [[gnu::always_inline]] friend Lanes3 operator*(const Lanes& s, const Lanes3& u) {
            return {s * u.x, s * u.y, s * u.z};
        }
        [[gnu::always_inline]] friend Lanes3 operator+(const Lanes3& u, const Lanes3& v) {
            return {u.x + v.x, u.y + v.y, u.z + v.z};
        }
        [[gnu::always_inline]] friend Lanes3 operator-(const Lanes3& u, const Lanes3& v) {
            return {u.x - v.x, u.y - v.y, u.z - v.z};
        }
    };
    struct Frames {
        Lanes3 origin, dir_x, dir_y, normal;
        Lanes x1, x2, y2;
    };
    static constexpr std::int64_t kSign = std::numeric_limits<std::int64_t>::min();  // bit 63

    // v in lane 0, shuffled to every lane: one broadcast from v's place in memory. A
    // constant is written into each lane instead, which GCC folds into a vector constant
    // (it broadcasts a shuffled one again at each use).
    [[gnu::always_inline]] static Lanes every(double v) {
        if (__builtin_constant_p(v)) {
            Lanes lanes;
            for (int k = 0; k < N; ++k) lanes[k] = v;
            return lanes;
        }
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
    // |v|, as fabs gives it: the sign bit cleared.
    [[gnu::always_inline]] static Lanes abs(const Lanes& v) {
        return from_bits(to_bits(v) & ~kSign);
    }
    // Lane k: where(k) ? a[k] : b[k], by bits.
    [[gnu::always_inline]] static Lanes select(const Mask& where, const Lanes& a, const Lanes& b) {
        return from_bits((to_bits(a) & where) | (to_bits(b) & ~where));
    }
    // Bit k where lane k holds. A branch a lane, not `(m[k] != 0 ? 1u : 0u) << k`: GCC 12
    // with UBSan's shift and bounds checks (the asan preset) reads that shift's count from a
    // copy of k it never initialises, so the bits land in the wrong lanes (see the lanes'
    // UBSan tests in tests/collision and tests/geometry).
    [[gnu::always_inline]] static unsigned bits(const Mask& m) {
        unsigned b = 0;
        for (int k = 0; k < N; ++k)
            if (m[k] != 0) b |= 1u << k;
        return b;
    }
    // The value at `field` of each object, object k in lane k.
    template <class T>
    [[gnu::always_inline]] static Lanes gather(const T* const (&p)[N], double T::*field) {
        Lanes v{};
        for (int k = 0; k < N; ++k) v[k] = p[k]->*field;
        return v;
    }
    template <class T>
    [[gnu::always_inline]] static Lanes3 gather(const T* const (&p)[N], glm::dvec3 T::*field) {
        Lanes3 v{};
        for (int k = 0; k < N; ++k) {
            const glm::dvec3& q = p[k]->*field;
            v.x[k] = q.x;
            v.y[k] = q.y;
            v.z[k] = q.z;
        }
        return v;
    }
    [[gnu::always_inline]] static Lanes3 gather(const glm::dvec3* const (&p)[N]) {
        Lanes3 v{};
        for (int k = 0; k < N; ++k) {
            v.x[k] = p[k]->x;
            v.y[k] = p[k]->y;
            v.z[k] = p[k]->z;
        }
        return v;
    }
    // The frames' values, frame k in lane k. Four lanes read each frame as the 15 doubles
    // it is laid out as, in rows of four (the last row, doubles 11-14, ends at the frame's
    // end); two lanes a value at a time, a load and a load-high each.
    [[gnu::always_inline]] static Frames frames(const NormalizedTriangle* const (&t)[N]) {
        using F = NormalizedTriangle;
        if constexpr (N == 4) {
            constexpr std::size_t d = sizeof(double);
            static_assert(sizeof(F) == 15 * d && offsetof(F, origin) == 0 &&
                          offsetof(F, dir_x) == 3 * d && offsetof(F, dir_y) == 6 * d &&
                          offsetof(F, normal) == 9 * d && offsetof(F, x1) == 12 * d &&
                          offsetof(F, x2) == 13 * d && offsetof(F, y2) == 14 * d);
            const Columns4 a = transposed(t, 0);
            const Columns4 b = transposed(t, 4);
            const Columns4 c = transposed(t, 8);
            const Columns4 d11 = transposed(t, 11);
            return {{a.c0, a.c1, a.c2},
                    {a.c3, b.c0, b.c1},
                    {b.c2, b.c3, c.c0},
                    {c.c1, c.c2, c.c3},
                    d11.c1,
                    d11.c2,
                    d11.c3};
        } else {
            return {gather(t, &F::origin), gather(t, &F::dir_x), gather(t, &F::dir_y),
                    gather(t, &F::normal), gather(t, &F::x1),    gather(t, &F::x2),
                    gather(t, &F::y2)};
        }
    }
    // glm::dot's order: (x + y) + z.
    [[gnu::always_inline]] static Lanes dot(const Lanes3& u, const Lanes3& v) {
        return u.x * v.x + u.y * v.y + u.z * v.z;
    }
    [[gnu::always_inline]] static Lanes sqrt(const Lanes& v) {
        Lanes root{};
        for (int k = 0; k < N; ++k) root[k] = std::sqrt(v[k]);
        return root;
    }
    // Lane k into out[k], by memcpy (a bit_cast took a detour through the stack).
    [[gnu::always_inline]] static std::array<double, N> stored(const Lanes& v) {
        std::array<double, N> out;
        std::memcpy(out.data(), &v, sizeof v);
        return out;
    }

  private:
    struct Columns4 {
        Lanes c0, c1, c2, c3;
    };
    // Doubles i to i + 3 of a frame (its layout is checked in frames), by memcpy: a frame is
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
};

}  // namespace trackphys::detail
