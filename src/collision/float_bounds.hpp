#pragma once

// Double bounds rounded to float in a chosen direction (private). The BVH keeps float boxes
// that must hold the exact double boxes (rounded outward), and queries compare their double
// boxes with those floats through a box rounded both ways: outward for tests that may only
// err toward "maybe", inward for tests that must be sure.

#include <bit>
#include <cstdint>
#include <limits>

#include <emmintrin.h>

#include "trackphys/geometry/aabb.hpp"

namespace trackphys::collision_detail {

/// x rounded to the nearest float. Through a volatile: GCC 12.2 at -O2 (SLP vectoriser)
/// folds (double)(float)x back to x for neighbouring components, which would make the
/// exactness checks below see no rounding at all and round nothing.
inline float nearest_float(double x) {
    volatile float f = static_cast<float>(x);
    return f;
}

/// The next float toward -infinity (f finite or +infinity, as nearest_float gives it above
/// x). Branch-free (a query rounds its six bounds both ways, each way a coin flip): on the
/// bits, negative floats (and -0) step up, positive ones down, +0 goes to the negative
/// denormal closest to 0.
inline float float_below(float f) {
    const auto bits = std::bit_cast<std::uint32_t>(f);
    std::uint32_t below = (bits >> 31) != 0 ? bits + 1 : bits - 1;
    below = bits == 0 ? 0x8000'0001u : below;
    return std::bit_cast<float>(below);
}

/// The next float toward +infinity (f finite or -infinity).
inline float float_above(float f) { return -float_below(-f); }

/// `then` where `condition` holds, else `otherwise`, on the bits (no branch).
inline float select(bool condition, float then, float otherwise) {
    const std::uint32_t mask = 0u - static_cast<std::uint32_t>(condition);
    return std::bit_cast<float>((std::bit_cast<std::uint32_t>(then) & mask) |
                                (std::bit_cast<std::uint32_t>(otherwise) & ~mask));
}

/// The largest float <= x (tight: x < float_above(result)); NaN stays NaN.
inline float round_down(double x) {
    const float f = nearest_float(x);
    return select(static_cast<double>(f) > x, float_below(f), f);
}

/// The smallest float >= x (tight: float_below(result) < x); NaN stays NaN.
inline float round_up(double x) {
    const float f = nearest_float(x);
    return select(static_cast<double>(f) < x, float_above(f), f);
}

/// A box in float, 24 bytes.
struct FloatBox {
    float min[3];
    float max[3];
};
static_assert(sizeof(FloatBox) == 24);

/// The smallest float box that contains `box`: each bound rounded outward (down for min, up
/// for max), so tests against it never reject what the double box would accept. Tight
/// rounding matters too: the triangle test's sure-accept (bvh_lanes.hpp) relies on it.
inline FloatBox outward_float_box(const Aabb& box) {
    FloatBox out;
    for (int a = 0; a < 3; ++a) {
        out.min[a] = round_down(box.min[a]);
        out.max[a] = round_up(box.max[a]);
    }
    return out;
}

/// The largest float box inside `box`: each bound rounded inward.
inline FloatBox inward_float_box(const Aabb& box) {
    FloatBox out;
    for (int a = 0; a < 3; ++a) {
        out.min[a] = round_up(box.min[a]);
        out.max[a] = round_down(box.max[a]);
    }
    return out;
}

namespace rounding_detail {

/// float_below on four lanes of float bits (the same steps, no branch).
inline __m128i below_bits(__m128i bits) {
    const __m128i negative = _mm_srai_epi32(bits, 31);
    // +1 for negative floats (and -0), -1 for positive ones; +0 goes to -denorm_min.
    const __m128i step =
        _mm_sub_epi32(_mm_and_si128(negative, _mm_set1_epi32(2)), _mm_set1_epi32(1));
    const __m128i zero = _mm_cmpeq_epi32(bits, _mm_setzero_si128());
    const __m128i below = _mm_add_epi32(bits, step);
    return _mm_or_si128(_mm_andnot_si128(zero, below),
                        _mm_and_si128(zero, _mm_set1_epi32(static_cast<int>(0x8000'0001u))));
}

/// Four lanes of floats f, nearest to the doubles x (lanes 0-1 of x01 and of x23): each
/// rounded down (`down`) and up (`up`), as round_down and round_up round them.
inline void round_lanes(__m128d x01, __m128d x23, __m128& down, __m128& up) {
    const __m128 f = _mm_movelh_ps(_mm_cvtpd_ps(x01), _mm_cvtpd_ps(x23));
    const __m128d back01 = _mm_cvtps_pd(f), back23 = _mm_cvtps_pd(_mm_movehl_ps(f, f));
    // The 64-bit masks packed to 32-bit lanes (each mask is all ones or zero).
    const __m128 above_x = _mm_castsi128_ps(_mm_packs_epi32(
        _mm_castpd_si128(_mm_cmpgt_pd(back01, x01)), _mm_castpd_si128(_mm_cmpgt_pd(back23, x23))));
    const __m128 below_x = _mm_castsi128_ps(_mm_packs_epi32(
        _mm_castpd_si128(_mm_cmplt_pd(back01, x01)), _mm_castpd_si128(_mm_cmplt_pd(back23, x23))));
    const __m128i sign = _mm_set1_epi32(static_cast<int>(0x8000'0000u));
    const __m128i bits = _mm_castps_si128(f);
    const __m128 step_down = _mm_castsi128_ps(below_bits(bits));
    const __m128 step_up =
        _mm_castsi128_ps(_mm_xor_si128(below_bits(_mm_xor_si128(bits, sign)), sign));  // -below(-f)
    down = _mm_or_ps(_mm_and_ps(above_x, step_down), _mm_andnot_ps(above_x, f));
    up = _mm_or_ps(_mm_and_ps(below_x, step_up), _mm_andnot_ps(below_x, f));
}

}  // namespace rounding_detail

/// outward_float_box and inward_float_box of `box` at once, in SSE2 (a query rounds its six
/// bounds both ways before its first node test): the same floats, bit for bit.
inline void round_both_ways(const Aabb& box, FloatBox& outward, FloatBox& inward) {
    alignas(16) float down[8], up[8];  // min x, y, z, max x | max y, z, -, -
    __m128 d, u;
    rounding_detail::round_lanes(_mm_set_pd(box.min.y, box.min.x), _mm_set_pd(box.max.x, box.min.z),
                                 d, u);
    _mm_store_ps(down, d);
    _mm_store_ps(up, u);
    rounding_detail::round_lanes(_mm_set_pd(box.max.z, box.max.y), _mm_setzero_pd(), d, u);
    _mm_store_ps(down + 4, d);
    _mm_store_ps(up + 4, u);
    outward = {{down[0], down[1], down[2]}, {up[3], up[4], up[5]}};
    inward = {{up[0], up[1], up[2]}, {down[3], down[4], down[5]}};
}

}  // namespace trackphys::collision_detail
