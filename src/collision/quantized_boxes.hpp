#pragma once

// Triangle boxes in 16 bits, relative to a box around their leaf lanes (private). A float
// box (the union of a subtree's lanes, shared by the nodes of that subtree, or of one
// node's leaf lanes: StaticCollider::quantize_slot_boxes) defines a grid per axis: a
// power-of-two step h and an integer base, so that grid index k stands for the coordinate
// k h and every triangle bound inside the box falls on a relative index in [1, 65534]. A
// triangle keeps, per bound, the relative index of its float bound rounded outward (min:
// floor, max: ceil): 12 bytes a triangle, in blocks of eight that one SSE2 16-bit compare
// per bound tests. Grids shared by a node's lanes (not per lane) let a query test
// neighbouring leaf lanes as one slot range (a block they share, once), and grids shared by
// a subtree let it quantize its box once for all the subtree's nodes it visits.
//
// Exactness. All arithmetic below is exact in double: x / h is a power-of-two scaling of a
// float (no overflow or underflow for |x| <= 1e18 and h >= 2^-149), and relative indices
// that matter are below 2^25 in magnitude. With T = [tmin, tmax] a triangle's exact double
// box, t = its tight float box (tmin_f <= tmin < float_above(tmin_f)), Q = its indices
// (absolute: Qmin = floor(tmin_f / h), Qmax = ceil(tmax_f / h)) and B the query box:
// - may overlap: Qmin <= ceil(B.max_out / h) and floor(B.min_out / h) <= Qmax, with B's
//   outward float bounds. T overlapping B gives Qmin h <= tmin <= B.max <= B.max_out <=
//   ceil(...) h; rejecting never loses a triangle.
// - surely overlaps: Qmin < floor(B.max_in / h) - 1 (and the mirror for max). The step is
//   at least the float spacing of the grid box's largest |coordinate|, so tmin <
//   float_above(tmin_f) <= tmin_f + h < (Qmin + 2) h <= floor(B.max_in / h) h <= B.max.
// Triangles that may overlap but not surely (within about two steps of a query bound) get
// the exact double test. The step is the smallest power of two that fits the grid box's
// extent into the index range, and never below that float spacing; a box flat on an axis
// (zero extent) gets the float spacing there (2^-149 at 0): no division by its extent.

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>

#include <emmintrin.h>

#include "float_bounds.hpp"
#include "trackphys/detail/bvh_node.hpp"

namespace trackphys::collision_detail {

/// Largest relative index a query bound is clamped to; triangle indices lie in [1, 65534],
/// so clamping to [0, kIndexLimit] changes no comparison with them.
inline constexpr int kIndexLimit = 65535;
/// Stored values are relative indices minus this (signed 16-bit compares, order kept).
inline constexpr int kIndexBias = 32768;

/// The grid of one node on one axis.
struct AxisGrid {
    double step;      ///< h (m), a power of two
    double inv_step;  ///< 1 / h, exact
    double base;      ///< absolute index of relative index 0 (an integer)
};

/// floor and ceil for |x| < 2^62 (SSE2 has no rounding instruction; libm calls are slow).
inline double floor_small(double x) {
    const auto t = static_cast<double>(static_cast<std::int64_t>(x));
    return t > x ? t - 1.0 : t;
}
inline double ceil_small(double x) {
    const auto t = static_cast<double>(static_cast<std::int64_t>(x));
    return t < x ? t + 1.0 : t;
}

/// The grid of a float box [lo, hi] on one axis (lo <= hi, finite).
inline AxisGrid axis_grid(float lo, float hi) {
    // Float spacing at the box's largest magnitude: 2^(exponent - 23), 2^-149 for denormals.
    const auto magnitude = std::bit_cast<std::uint32_t>(std::max(std::fabs(lo), std::fabs(hi)));
    const std::uint64_t exponent = std::max<std::uint32_t>((magnitude >> 23) & 0xffu, 1u);
    const double spacing = std::bit_cast<double>((exponent - 150u + 1023u) << 52);
    // Smallest power of two >= extent / 65530 (the margin absorbs the division's rounding):
    // floor(lo / h) .. ceil(hi / h) then spans at most 65531 steps, relative 1 .. 65532.
    const double need = (double(hi) - double(lo)) / 65530.0;
    auto bits = std::bit_cast<std::uint64_t>(need);
    constexpr std::uint64_t kMantissa = (std::uint64_t{1} << 52) - 1;
    if ((bits & kMantissa) != 0) bits = (bits & ~kMantissa) + (std::uint64_t{1} << 52);
    const double step = std::max(std::bit_cast<double>(bits), spacing);
    const double inv_step = 1.0 / step;
    return {step, inv_step, floor_small(double(lo) * inv_step) - 1.0};
}

/// Relative index of a float lower bound in the grid, rounded down (the grid value at it
/// is <= x).
inline int quantize_down(float x, const AxisGrid& g) {
    return static_cast<int>(floor_small(double(x) * g.inv_step) - g.base);
}
/// Relative index of a float upper bound, rounded up (the grid value at it is >= x).
inline int quantize_up(float x, const AxisGrid& g) {
    return static_cast<int>(ceil_small(double(x) * g.inv_step) - g.base);
}
/// The coordinate (m) of relative index k: exact.
inline double grid_value(int k, const AxisGrid& g) { return (g.base + k) * g.step; }

/// The layout of eight triangle boxes in 16 bits: v[bound][lane], bounds min x, y, z, max
/// x, y, z, each the biased relative index in its own node's grid (a block may straddle
/// nodes; queries only read the lanes of the node they test). 96 bytes.
struct QuantizedBlock {
    static constexpr std::uint32_t kLanes = 8;
    std::int16_t v[6][kLanes];
};
static_assert(sizeof(QuantizedBlock) == 96);

/// A node's grids as stored (BvhNodeGrid) -> AxisGrid of axis a.
inline AxisGrid axis_of(const BvhNodeGrid& g, int a) {
    return {1.0 / g.inv_step[a], g.inv_step[a], g.base[a]};
}
/// Three AxisGrids -> a node's grids as stored.
inline BvhNodeGrid node_grid(const AxisGrid (&g)[3]) {
    return {{g[0].inv_step, g[1].inv_step, g[2].inv_step}, {g[0].base, g[1].base, g[2].base}};
}

/// A query's float bounds, once per query, paired for the grid arithmetic: per axis, the
/// bounds to round down (outward min, inward max) and the negated ones to round up
/// (ceil(x) = -floor(-x): inward min, outward max).
struct QueryBounds {
    __m128d down[3], up_negated[3];

    QueryBounds(const FloatBox& out, const FloatBox& in) {
        for (int a = 0; a < 3; ++a) {
            down[a] = _mm_set_pd(in.max[a], out.min[a]);
            up_negated[a] = _mm_set_pd(-double(out.max[a]), -double(in.min[a]));
        }
    }
};

/// A query box in one node's grids, each bound in all eight lanes, biased: the outward
/// indices for "may overlap", and the inward ones narrowed by the proof's slack for "surely
/// overlaps". Each is clamped into [0, kIndexLimit], which changes no comparison with a
/// triangle's index (in [1, kIndexLimit - 1]).
struct QuantizedQuery {
    __m128i may_min[3], may_max[3], sure_min[3], sure_max[3];
};

namespace quantize_detail {

/// floor(x * inv_step) - base for two bounds, as int32 in lanes 0 and 1. x * inv_step is
/// exact (a power-of-two scaling); it is clamped into [lo, hi] first (integers a few steps
/// beyond the grid; NaN goes to lo), which changes no result once clamped to the index
/// range, and keeps the conversions in int32 range. Truncation rounds toward zero: the
/// compare steps negative fractions down. Every step is exact.
inline __m128i relative_floor(__m128d x, double inv_step, double lo, double hi, double base) {
    const __m128d scaled = _mm_mul_pd(x, _mm_set1_pd(inv_step));
    const __m128d y = _mm_min_pd(_mm_max_pd(scaled, _mm_set1_pd(lo)), _mm_set1_pd(hi));
    const __m128d truncated = _mm_cvtepi32_pd(_mm_cvttpd_epi32(y));
    const __m128d floored =
        _mm_sub_pd(truncated, _mm_and_pd(_mm_cmpgt_pd(truncated, y), _mm_set1_pd(1.0)));
    return _mm_cvttpd_epi32(_mm_sub_pd(floored, _mm_set1_pd(base)));
}

/// Lane k of four int16 values in all eight lanes.
template <int k>
inline __m128i broadcast16(__m128i v) {
    return _mm_shuffle_epi32(_mm_shufflelo_epi16(v, _MM_SHUFFLE(k, k, k, k)), 0);
}

}  // namespace quantize_detail

/// The query in a node's grids (SSE2, no division).
inline QuantizedQuery quantize_query(const QueryBounds& b, const BvhNodeGrid& g) {
    using namespace quantize_detail;
    QuantizedQuery q;
    // Relative indices per axis: floor(out.min), floor(in.max) - 1, ceil(in.min) + 1,
    // ceil(out.max); the up ones come negated, so they are negated back.
    const __m128i negate = _mm_set_epi32(-1, -1, 0, 0);
    const __m128i adjust = _mm_set_epi32(0, 1, -1, 0);
    const __m128i bias = _mm_set1_epi32(kIndexBias);
    for (int a = 0; a < 3; ++a) {
        // Clamped to 4 steps beyond [0, kIndexLimit] (for -x: the mirror image).
        const double lo = g.base[a] - 4.0, hi = g.base[a] + (kIndexLimit + 4.0);
        const __m128i down = relative_floor(b.down[a], g.inv_step[a], lo, hi, g.base[a]);
        const __m128i up = relative_floor(b.up_negated[a], g.inv_step[a], -hi, -lo, -g.base[a]);
        __m128i r = _mm_unpacklo_epi64(down, up);
        r = _mm_sub_epi32(_mm_xor_si128(r, negate), negate);
        r = _mm_sub_epi32(_mm_add_epi32(r, adjust), bias);
        // Signed saturation clamps the biased indices into [0, kIndexLimit] - kIndexBias.
        const __m128i packed = _mm_packs_epi32(r, r);
        q.may_min[a] = broadcast16<0>(packed);
        q.sure_max[a] = broadcast16<1>(packed);
        q.sure_min[a] = broadcast16<2>(packed);
        q.may_max[a] = broadcast16<3>(packed);
    }
    return q;
}

/// Bits 0-7: lane i of the block (QuantizedBlock's layout, any alignment) may overlap the
/// query; bits 8-15: lane i surely overlaps it.
inline unsigned test_block(const std::int16_t* block, const QuantizedQuery& q) {
    const auto* lanes = reinterpret_cast<const __m128i*>(block);
    __m128i miss = _mm_setzero_si128();
    __m128i sure = _mm_set1_epi16(-1);
    for (int a = 0; a < 3; ++a) {
        const __m128i lo = _mm_loadu_si128(lanes + a);
        const __m128i hi = _mm_loadu_si128(lanes + 3 + a);
        miss = _mm_or_si128(miss, _mm_or_si128(_mm_cmpgt_epi16(lo, q.may_max[a]),
                                               _mm_cmpgt_epi16(q.may_min[a], hi)));
        sure = _mm_and_si128(sure, _mm_and_si128(_mm_cmpgt_epi16(q.sure_max[a], lo),
                                                 _mm_cmpgt_epi16(hi, q.sure_min[a])));
    }
    const __m128i may = _mm_andnot_si128(miss, _mm_set1_epi16(-1));
    return static_cast<unsigned>(_mm_movemask_epi8(_mm_packs_epi16(may, sure)));
}

}  // namespace trackphys::collision_detail
