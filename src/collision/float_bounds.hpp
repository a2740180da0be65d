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

}  // namespace trackphys::collision_detail
