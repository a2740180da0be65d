// The directed float rounding behind the BVH's float boxes and its query boxes: each bound
// must be rounded the right way and tightly (a float step further breaks the sure-overlap
// test, a step short breaks containment).

#include "collision/float_bounds.hpp"

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include <gtest/gtest.h>

namespace trackphys {
namespace {

using collision_detail::round_down;
using collision_detail::round_up;

constexpr float kFloatInf = std::numeric_limits<float>::infinity();

// Down: result <= x < the next float up. Up: the next float down < x <= result.
void expect_tight(double x) {
    const float down = round_down(x), up = round_up(x);
    EXPECT_LE(double(down), x) << x;
    EXPECT_LT(x, double(std::nextafter(down, kFloatInf))) << x;
    EXPECT_GE(double(up), x) << x;
    EXPECT_GT(x, double(std::nextafter(up, -kFloatInf))) << x;
    // Exactly representable values stay put; others land on neighbouring floats.
    if (double(float(x)) == x) {
        EXPECT_EQ(down, float(x));
        EXPECT_EQ(up, float(x));
    } else {
        EXPECT_EQ(std::nextafter(down, kFloatInf), up) << x;
    }
}

TEST(FloatBounds, RoundsEachWayTightly) {
    for (double x :
         {0.1, -0.1, 1.0 / 3.0, -2.0 / 3.0, 0.25, -0.25, 1.0, 16777217.0, -16777217.0, 1e-30,
          -1e-30, 1e-45, -1e-45, 123456.789, -98765.4321, 1e18, -1e18, 3.4e38, -3.4e38})
        expect_tight(x);
    // Around coordinates of a large world, where a float step is millimetres.
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> coordinate(-40000.0, 40000.0);
    for (int i = 0; i < 10000; ++i) expect_tight(coordinate(rng));
}

TEST(FloatBounds, ZeroInfinityAndNaN) {
    EXPECT_EQ(round_down(0.0), 0.0f);
    EXPECT_EQ(round_up(-0.0), 0.0f);
    EXPECT_EQ(round_down(1e-300), 0.0f);
    EXPECT_EQ(round_up(1e-300), std::numeric_limits<float>::denorm_min());
    EXPECT_EQ(round_down(-1e-300), -std::numeric_limits<float>::denorm_min());
    EXPECT_EQ(round_down(1e300), std::numeric_limits<float>::max());
    EXPECT_EQ(round_up(1e300), kFloatInf);
    EXPECT_EQ(round_down(-1e300), -kFloatInf);
    EXPECT_EQ(round_up(-1e300), -std::numeric_limits<float>::max());
    const double inf = std::numeric_limits<double>::infinity();
    EXPECT_EQ(round_down(inf), kFloatInf);
    EXPECT_EQ(round_up(-inf), -kFloatInf);
    EXPECT_TRUE(std::isnan(round_down(std::nan(""))));
    EXPECT_TRUE(std::isnan(round_up(std::nan(""))));
}

// Three neighbouring components rounded together, the pattern GCC 12.2's SLP vectoriser
// miscompiles without the volatile in nearest_float: every bound must still move.
TEST(FloatBounds, BoxesRoundEveryComponent) {
    const Aabb box{{0.1, 0.2, 0.3}, {0.7, 0.8, 0.9}};
    const collision_detail::FloatBox out = collision_detail::outward_float_box(box);
    const collision_detail::FloatBox in = collision_detail::inward_float_box(box);
    for (int a = 0; a < 3; ++a) {
        EXPECT_LT(double(out.min[a]), box.min[a]);
        EXPECT_GT(double(out.max[a]), box.max[a]);
        EXPECT_GT(double(in.min[a]), box.min[a]);
        EXPECT_LT(double(in.max[a]), box.max[a]);
    }
}

// The SSE2 rounding of a query box both ways gives the scalar roundings' floats bit for
// bit: on the values above, signed zeros, infinities, NaN and random doubles of every
// magnitude from below the float denormals to beyond the float range.
TEST(FloatBounds, BothWaysMatchesScalar) {
    const double inf = std::numeric_limits<double>::infinity();
    std::vector<double> values{0.0,         -0.0,  0.1,    -0.1,        1.0 / 3.0, 16777217.0,
                               -16777217.0, 1e-30, -1e-30, 1e-45,       -1e-45,    1e-300,
                               -1e-300,     1e18,  -1e18,  3.4e38,      -3.4e38,   1e300,
                               -1e300,      inf,   -inf,   std::nan("")};
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> mantissa(-1.0, 1.0);
    std::uniform_int_distribution<int> exponent(-160, 140);
    for (int i = 0; i < 3000; ++i) values.push_back(std::ldexp(mantissa(rng), exponent(rng)));
    const auto bits = [](float f) { return std::bit_cast<std::uint32_t>(f); };
    for (std::size_t i = 0; i + 5 < values.size(); ++i) {
        const Aabb box{{values[i], values[i + 1], values[i + 2]},
                       {values[i + 3], values[i + 4], values[i + 5]}};
        collision_detail::FloatBox out, in;
        collision_detail::round_both_ways(box, out, in);
        const collision_detail::FloatBox out_ref = collision_detail::outward_float_box(box);
        const collision_detail::FloatBox in_ref = collision_detail::inward_float_box(box);
        for (int a = 0; a < 3; ++a) {
            EXPECT_EQ(bits(out.min[a]), bits(out_ref.min[a])) << box.min[a];
            EXPECT_EQ(bits(out.max[a]), bits(out_ref.max[a])) << box.max[a];
            EXPECT_EQ(bits(in.min[a]), bits(in_ref.min[a])) << box.min[a];
            EXPECT_EQ(bits(in.max[a]), bits(in_ref.max[a])) << box.max[a];
        }
    }
}

}  // namespace
}  // namespace trackphys
