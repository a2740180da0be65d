#pragma once

// Double bounds rounded to float in a chosen direction (private). The BVH keeps float boxes
// that must hold the exact double boxes (rounded outward), and queries compare their double
// boxes with those floats through a box rounded both ways: outward for tests that may only
// err toward "maybe", inward for tests that must be sure.

#include <bit>
#include <cstdint>
#include <limits>

#include "trackphys/geometry/aabb.hpp"

namespace trackphys::collision_detail {

/// x rounded to the nearest float. Through a volatile: GCC 12.2 at -O2 (SLP vectoriser)
/// folds (double)(float)x back to x for neighbouring components, which would make the
/// exactness checks below see no rounding at all and round nothing.
inline float nearest_float(double x) {
    volatile float f = static_cast<float>(x);
    return f;
}

/// The next float toward -infinity (f finite or +infinity, as nearest_float gives it above x).
inline float float_below(float f) {
    if (f == 0.0f) return -std::numeric_limits<float>::denorm_min();
    const auto bits = std::bit_cast<std::uint32_t>(f);
    return std::bit_cast<float>(f > 0.0f ? bits - 1 : bits + 1);
}

/// The next float toward +infinity (f finite or -infinity).
inline float float_above(float f) { return -float_below(-f); }

/// The largest float <= x (tight: x < float_above(result)); NaN stays NaN.
inline float round_down(double x) {
    const float f = nearest_float(x);
    return static_cast<double>(f) > x ? float_below(f) : f;
}

/// The smallest float >= x (tight: float_below(result) < x); NaN stays NaN.
inline float round_up(double x) {
    const float f = nearest_float(x);
    return static_cast<double>(f) < x ? float_above(f) : f;
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

}  // namespace trackphys::collision_detail
