// The 16-bit triangle boxes of StaticCollider's leaves (src/collision/quantized_boxes.hpp):
// grids that hold every bound of their box in the index range, outward and tight rounding
// of triangle bounds, the SIMD query quantization against a scalar statement of it, and
// the block test's two answers against exact double overlap ("may" never misses, "surely"
// never lies), at box borders, on flat boxes and at huge coordinates.

#include "collision/quantized_boxes.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "collision/float_bounds.hpp"

namespace trackphys {
namespace {

using collision_detail::axis_grid;
using collision_detail::AxisGrid;
using collision_detail::grid_value;
using collision_detail::kIndexBias;
using collision_detail::kIndexLimit;
using collision_detail::quantize_down;
using collision_detail::quantize_up;

constexpr float kInfinity = std::numeric_limits<float>::infinity();

// Grids of [lo, hi] boxes: ordinary, at huge coordinates, straddling 0, and flat ones
// (zero extent: at 0, at a denormal, at 1e18, at a negative value).
const std::vector<std::pair<float, float>> kBoxes = {
    {-3.25f, 7.5f},  {1000.0f, 1000.125f}, {-1e18f, 1e18f},  {9.9e17f, 1e18f},
    {-1e-3f, 2e-3f}, {0.0f, 0.0f},         {1e-44f, 1e-44f}, {1e18f, 1e18f},
    {-5.5f, -5.5f},  {-1e6f, -999999.9f},  {0.0f, 1e-40f},   {-7.0f, 0.0f},
};

// A grid's step is a power of two, at least the float spacing at the box's magnitude and
// enough to span the box: every bound in [lo, hi] lands on an index in [1, kIndexLimit - 1].
TEST(QuantizedBoxes, GridsHoldTheirBox) {
    for (const auto& [lo, hi] : kBoxes) {
        const AxisGrid g = axis_grid(lo, hi);
        ASSERT_GT(g.step, 0.0) << lo << " " << hi;
        ASSERT_TRUE(std::isfinite(g.step) && std::isfinite(g.inv_step));
        int exponent = 0;
        EXPECT_EQ(std::frexp(g.step, &exponent), 0.5) << "step not a power of two";
        EXPECT_EQ(g.step * g.inv_step, 1.0);
        EXPECT_EQ(g.base, std::floor(g.base));
        const float magnitude = std::max(std::fabs(lo), std::fabs(hi));
        EXPECT_GE(g.step, double(std::nextafter(magnitude, kInfinity)) - magnitude);
        for (const float x : {lo, hi}) {
            for (const int k : {quantize_down(x, g), quantize_up(x, g)}) {
                EXPECT_GE(k, 1) << x;
                EXPECT_LE(k, kIndexLimit - 1) << x;
            }
        }
        if (lo == hi) {
            EXPECT_EQ(quantize_down(lo, g), quantize_up(hi, g));
        }
    }
}

// Min bounds round down, max bounds up, each by less than a step: grid(k) <= x <
// grid(k + 1) and grid(k - 1) < x <= grid(k). Exact grid points stay put.
TEST(QuantizedBoxes, RoundsOutwardAndTightly) {
    std::mt19937 rng(17);
    for (const auto& [lo, hi] : kBoxes) {
        const AxisGrid g = axis_grid(lo, hi);
        std::uniform_real_distribution<double> u(lo, hi);
        std::vector<float> xs = {lo, hi, std::nextafter(lo, kInfinity),
                                 std::nextafter(hi, -kInfinity)};
        for (int i = 0; i < 2000; ++i) xs.push_back(static_cast<float>(u(rng)));
        for (float x : xs) {
            x = std::clamp(x, lo, hi);
            const int down = quantize_down(x, g), up = quantize_up(x, g);
            EXPECT_LE(grid_value(down, g), double(x)) << x;
            EXPECT_LT(double(x), grid_value(down + 1, g)) << x;
            EXPECT_GE(grid_value(up, g), double(x)) << x;
            EXPECT_GT(double(x), grid_value(up - 1, g)) << x;
            if (grid_value(down, g) == double(x)) {
                EXPECT_EQ(down, up);
            }
        }
    }
}

// The SIMD quantization equals its scalar statement: may_min = floor(out.min / h), may_max
// = ceil(out.max / h), sure_min = ceil(in.min / h) + 1, sure_max = floor(in.max / h) - 1,
// relative to the base, clamped into [0, kIndexLimit], biased.
std::int16_t expected_lane(double index) {
    const double clamped = std::clamp(index, 0.0, double(kIndexLimit));
    return static_cast<std::int16_t>(static_cast<int>(clamped) - kIndexBias);
}

void expect_lanes(__m128i v, std::int16_t want, const char* what, float x) {
    alignas(16) std::int16_t lanes[8];
    _mm_store_si128(reinterpret_cast<__m128i*>(lanes), v);
    for (const std::int16_t lane : lanes) ASSERT_EQ(lane, want) << what << " at " << x;
}

TEST(QuantizedBoxes, QueryQuantizationMatchesScalar) {
    std::mt19937 rng(23);
    for (const auto& [lo, hi] : kBoxes) {
        const AxisGrid axis = axis_grid(lo, hi);
        const AxisGrid grids[3] = {axis, axis, axis};
        const BvhNodeGrid node = collision_detail::node_grid(grids);
        const double span = std::max(double(hi) - double(lo), 1e-30);
        std::uniform_real_distribution<double> u(double(lo) - span, double(hi) + span);
        std::vector<float> xs = {lo,
                                 hi,
                                 std::nextafter(lo, -kInfinity),
                                 std::nextafter(hi, kInfinity),
                                 0.0f,
                                 -0.0f,
                                 kInfinity,
                                 -kInfinity,
                                 3e38f,
                                 -3e38f,
                                 1e-45f,
                                 -1e-45f};
        for (int i = 0; i < 500; ++i) xs.push_back(static_cast<float>(u(rng)));
        for (const float x : xs) {
            // The same bound as every query bound: each lane's rounding shows in isolation.
            const collision_detail::FloatBox box{{x, x, x}, {x, x, x}};
            const collision_detail::QuantizedQuery q =
                collision_detail::quantize_query(collision_detail::QueryBounds(box, box), node);
            const double scaled = double(x) * axis.inv_step;
            const double floor_rel = std::floor(scaled) - axis.base;
            const double ceil_rel = std::ceil(scaled) - axis.base;
            for (int a = 0; a < 3; ++a) {
                expect_lanes(q.may_min[a], expected_lane(floor_rel), "may_min", x);
                expect_lanes(q.may_max[a], expected_lane(ceil_rel), "may_max", x);
                expect_lanes(q.sure_min[a], expected_lane(ceil_rel + 1.0), "sure_min", x);
                expect_lanes(q.sure_max[a], expected_lane(floor_rel - 1.0), "sure_max", x);
            }
        }
    }
}

// Exact double boxes of "triangles" inside a node box and double query boxes, many of them
// touching or a float step off each other's bounds: bit i of "may" is set whenever box i
// overlaps the query, bit i of "surely" only when it does; and both decide every clear
// case (overlap or gap of at least four steps on an axis), so the exact test only sees
// boxes near a bound.
TEST(QuantizedBoxes, BlockTestIsConservativeBothWays) {
    std::mt19937_64 rng(31);
    std::size_t clear_cases = 0;
    for (const auto& [lo, hi] : kBoxes) {
        const AxisGrid axis = axis_grid(lo, hi);
        const AxisGrid grids[3] = {axis, axis, axis};
        const BvhNodeGrid node = collision_detail::node_grid(grids);
        std::uniform_real_distribution<double> inside(lo, hi);
        const double span = double(hi) - double(lo);
        std::uniform_real_distribution<double> around(double(lo) - 0.2 * span,
                                                      double(hi) + 0.2 * span);
        for (int round = 0; round < 400; ++round) {
            Aabb tris[8];
            alignas(16) std::int16_t block[6][8];
            for (int t = 0; t < 8; ++t) {
                for (int a = 0; a < 3; ++a) {
                    double p = inside(rng), r = inside(rng);
                    if (p > r) std::swap(p, r);
                    tris[t].min[a] = p;
                    tris[t].max[a] = r;
                }
                const collision_detail::FloatBox f = collision_detail::outward_float_box(tris[t]);
                for (int a = 0; a < 3; ++a) {
                    block[a][t] =
                        static_cast<std::int16_t>(quantize_down(f.min[a], axis) - kIndexBias);
                    block[3 + a][t] =
                        static_cast<std::int16_t>(quantize_up(f.max[a], axis) - kIndexBias);
                }
            }
            // Query bounds: random, or exactly at / just beyond a triangle's bound.
            Aabb query;
            for (int a = 0; a < 3; ++a) {
                double p = around(rng), r = around(rng);
                if (p > r) std::swap(p, r);
                const Aabb& t = tris[rng() % 8];
                switch (rng() % 4) {
                    case 0:
                        r = std::max(p, t.min[a]);
                        break;  // touches
                    case 1:
                        r = std::max(p, std::nextafter(t.min[a], -1e300));
                        break;  // just misses
                    case 2:
                        p = std::min(r, t.max[a]);
                        break;
                    default:
                        break;
                }
                query.min[a] = p;
                query.max[a] = r;
            }
            const collision_detail::QuantizedQuery q = collision_detail::quantize_query(
                collision_detail::QueryBounds(collision_detail::outward_float_box(query),
                                              collision_detail::inward_float_box(query)),
                node);
            const unsigned bits = collision_detail::test_block(&block[0][0], q);
            const double margin = 4.0 * axis.step;
            for (int t = 0; t < 8; ++t) {
                const bool may = ((bits >> t) & 1u) != 0, surely = ((bits >> (8 + t)) & 1u) != 0;
                bool deep = true, far = false;
                for (int a = 0; a < 3; ++a) {
                    const double in_overlap =
                        std::min(query.max[a] - tris[t].min[a], tris[t].max[a] - query.min[a]);
                    deep = deep && in_overlap >= margin;
                    far = far || in_overlap <= -margin;
                }
                if (tris[t].overlaps(query)) {
                    ASSERT_TRUE(may) << "missed a box, grid [" << lo << ", " << hi << "]";
                } else {
                    ASSERT_FALSE(surely) << "false sure overlap, grid [" << lo << ", " << hi << "]";
                }
                if (deep) {
                    ASSERT_TRUE(surely) << "undecided deep overlap";
                }
                if (far) {
                    ASSERT_FALSE(may) << "undecided clear miss";
                }
                clear_cases += deep || far;
            }
        }
    }
    EXPECT_GT(clear_cases, 1000u);
}

}  // namespace
}  // namespace trackphys
