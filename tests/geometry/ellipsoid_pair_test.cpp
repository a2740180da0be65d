#include "trackphys/geometry/ellipsoid_pair.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "geometry/ellipsoid_pair_kernel.hpp"
#include "support/ellipsoid_pair_cases.hpp"
#include "support/ellipsoid_pair_contract.hpp"
#include "support/ellipsoid_pair_reference.hpp"

namespace trackphys {
namespace {

using test::angle;
using test::depth_tolerance;
using test::describe;
using test::finite;
using test::KindStats;
using test::largest_axis;
using test::PairCase;
using test::PairCaseGenerator;
using test::PairKind;

using test::kSanitized;

/// The pair count per family: 1000 (11k in all), 150 under AddressSanitizer, or
/// TRACKPHYS_PAIR_CASES.
int cases_per_kind() {
    const char* text = std::getenv("TRACKPHYS_PAIR_CASES");
    const int count = text ? std::atoi(text) : 0;
    return count > 0 ? count : kSanitized ? 150 : 1000;
}

void check_case(const PairCase& c, KindStats& stats) {
    const Contact got = ellipsoid_ellipsoid_contact(c.a, c.b);
    test::PairReference solver(c.a, c.b);
    const test::PairReferenceResult ref = solver.solve();
    test::check_contract(c, got, ref, stats);
    if (::testing::Test::HasFatalFailure()) return;
    // Every family's minimum is proven, and its proven lower bound is one.
    const detail::PairSolution solution = detail::pair_solution(c.a, c.b);
    ASSERT_NE(solution.path, detail::PairPath::unproven) << describe(c);
    const double unit = got.depth / solution.depth;  // the frame's power of two
    if (std::isfinite(unit) && unit > 0.0) {
        const double magnitude = std::max(std::abs(double(ref.depth)), largest_axis(c.a, c.b));
        ASSERT_LE(solution.lower_bound * unit, double(ref.depth) + depth_tolerance(magnitude))
            << describe(c);
    }
}

TEST(EllipsoidPair, MatchesTheLongDoubleReferenceOnEveryFamily) {
    PairCaseGenerator generator(20261126);
    std::map<PairKind, KindStats> stats;
    const int per_kind = cases_per_kind();
    for (int k = 0; k < static_cast<int>(PairKind::count); ++k)
        for (int i = 0; i < per_kind; ++i) {
            const PairCase c = generator.make(static_cast<PairKind>(k));
            check_case(c, stats[c.kind]);
            if (HasFatalFailure()) return;
        }
    std::printf("family            cases  unique  max|depth err|  max angle  max point err\n");
    for (const auto& [kind, s] : stats) {
        std::printf("%-16s %6ld  %6ld  %13.3g  %9.3g  %13.3g\n", test::pair_kind_name(kind),
                    s.cases, s.unique, s.depth_error, s.angle_error, s.point_error);
        // Every family has cases with a unique minimiser, whose direction was checked.
        if (kind != PairKind::coincident) {
            EXPECT_GT(s.unique, 0) << test::pair_kind_name(kind);
        }
    }
}

TEST(EllipsoidPair, SpheresMatchTheClosedForm) {
    PairCaseGenerator generator(7);
    for (int i = 0; i < 2000; ++i) {
        const PairCase c = generator.make(PairKind::spheres);
        const Contact got = ellipsoid_ellipsoid_contact(c.a, c.b);
        const glm::dvec3 d = c.a.center() - c.b.center();
        const double distance = glm::length(d);
        const double want = c.a.semi_axes().x + c.b.semi_axes().x - distance;
        ASSERT_NEAR(got.depth, want, 1e-12) << describe(c);
        if (distance > 1e-6) {
            ASSERT_LE(angle(got.normal, d / distance), 1e-9) << describe(c);
        }
    }
}

}  // namespace
}  // namespace trackphys

namespace trackphys {
namespace {

/// h at -normal in double: the support of A - B in the direction the contact's normal
/// says. A normal that minimises h gives back the depth.
double support_at_normal(const Ellipsoid& a, const Ellipsoid& b, const glm::dvec3& normal) {
    const glm::dvec3 n = -normal;
    const glm::dvec3 xa = PairCaseGenerator::support_point(a, n) - a.center();
    const glm::dvec3 xb = PairCaseGenerator::support_point(b, -n) - b.center();
    return glm::dot(a.center() - b.center(), n) + glm::dot(xa, n) - glm::dot(xb, n);
}

std::vector<PairCase> mixed_cases(std::uint64_t seed, int per_kind) {
    PairCaseGenerator generator(seed);
    std::vector<PairCase> out;
    for (int k = 0; k < static_cast<int>(PairKind::count); ++k)
        for (int i = 0; i < per_kind; ++i) out.push_back(generator.make(static_cast<PairKind>(k)));
    return out;
}

TEST(EllipsoidPair, SwappingTheArgumentsNegatesTheNormalBitForBit) {
    for (const PairCase& c : mixed_cases(11, 200)) {
        const Contact ab = ellipsoid_ellipsoid_contact(c.a, c.b);
        const Contact ba = ellipsoid_ellipsoid_contact(c.b, c.a);
        ASSERT_EQ(std::bit_cast<std::uint64_t>(ab.depth), std::bit_cast<std::uint64_t>(ba.depth))
            << describe(c);
        for (int i = 0; i < 3; ++i) {
            ASSERT_EQ(ab.normal[i], -ba.normal[i]) << describe(c);
            ASSERT_EQ(std::bit_cast<std::uint64_t>(ab.point[i]),
                      std::bit_cast<std::uint64_t>(ba.point[i]))
                << describe(c);
        }
    }
}

TEST(EllipsoidPair, RigidMotionsKeepTheDepthAndCarryTheNormal) {
    PairCaseGenerator motions(12);
    for (const PairCase& c : mixed_cases(13, 150)) {
        const glm::dquat q = motions.rotation();
        const glm::dvec3 t = motions.unit_vector() * motions.uniform(0.0, 100.0);
        const Ellipsoid a = c.a.transformed(q, t), b = c.b.transformed(q, t);
        const Contact before = ellipsoid_ellipsoid_contact(c.a, c.b);
        const Contact after = ellipsoid_ellipsoid_contact(a, b);
        const double magnitude = std::max({std::abs(before.depth), largest_axis(a, b), 100.0});
        const double tolerance = 1e-12 * magnitude;
        ASSERT_NEAR(after.depth, before.depth, tolerance) << describe(c);
        // The moved normal, carried back, minimises the original pair's h (a rotated copy of
        // the original normal when the minimiser is unique, another minimiser otherwise).
        const glm::dvec3 back = glm::inverse(q) * after.normal;
        ASSERT_NEAR(support_at_normal(c.a, c.b, back), before.depth, tolerance) << describe(c);
    }
}

TEST(EllipsoidPair, PermutedSemiAxesWithTheMatchingRotationChangeNothing) {
    // (x, y, z) -> (y, z, x) with the third of a turn about (1, 1, 1), and (x, y, z) ->
    // (y, x, z) with a quarter turn about z: the same solid, described differently.
    const glm::dquat cycle(0.5, 0.5, 0.5, 0.5);
    const glm::dquat swap = glm::angleAxis(1.5707963267948966, glm::dvec3(0.0, 0.0, 1.0));
    const auto cycled = [&](const Ellipsoid& e) {
        const glm::dvec3 r = e.semi_axes();
        return Ellipsoid(e.center(), e.orientation() * cycle, {r.y, r.z, r.x});
    };
    const auto swapped = [&](const Ellipsoid& e) {
        const glm::dvec3 r = e.semi_axes();
        return Ellipsoid(e.center(), e.orientation() * swap, {r.y, r.x, r.z});
    };
    for (const PairCase& c : mixed_cases(14, 150)) {
        const Contact base = ellipsoid_ellipsoid_contact(c.a, c.b);
        const double tolerance = 1e-12 * std::max(std::abs(base.depth), largest_axis(c.a, c.b));
        for (const Contact& other : {ellipsoid_ellipsoid_contact(cycled(c.a), swapped(c.b)),
                                     ellipsoid_ellipsoid_contact(swapped(c.a), cycled(c.b))}) {
            ASSERT_NEAR(other.depth, base.depth, tolerance) << describe(c);
            ASSERT_NEAR(support_at_normal(c.a, c.b, other.normal), base.depth, tolerance)
                << describe(c);
        }
    }
}

Ellipsoid scaled_by(double s, const Ellipsoid& e) {
    return Ellipsoid(e.center() * s, e.orientation(), e.semi_axes() * s);
}

// Every length is divided by a power of two before the solver runs, so a power-of-two scale
// of the input scales the answer exactly, from 2^-500 to 2^500.
TEST(EllipsoidPair, PowerOfTwoScalesScaleTheContactExactly) {
    const std::vector<PairCase> cases = mixed_cases(15, 40);
    for (const int exponent : {-500, -100, -20, -1, 1, 20, 100, 500}) {
        const double s = std::ldexp(1.0, exponent);
        for (const PairCase& c : cases) {
            // Both built from the same quaternion (normalising a unit one again may move its
            // last bits).
            const Contact base =
                ellipsoid_ellipsoid_contact(scaled_by(1.0, c.a), scaled_by(1.0, c.b));
            const Contact got = ellipsoid_ellipsoid_contact(scaled_by(s, c.a), scaled_by(s, c.b));
            ASSERT_EQ(got.depth, base.depth * s) << describe(c) << " scale 2^" << exponent;
            ASSERT_EQ(got.normal, base.normal) << describe(c) << " scale 2^" << exponent;
            ASSERT_EQ(got.point, base.point * s) << describe(c) << " scale 2^" << exponent;
        }
    }
}

TEST(EllipsoidPair, NoFiniteInputMakesNaN) {
    PairCaseGenerator generator(16);
    const auto any_length = [&] { return std::pow(10.0, generator.uniform(-300.0, 300.0)); };
    const auto any_coordinate = [&] {
        const double x = generator.uniform(0, 1);
        if (x < 0.1) return 0.0;
        if (x < 0.15) return std::numeric_limits<double>::max() * (x < 0.125 ? 1 : -1);
        return any_length() * (generator.uniform(0, 1) < 0.5 ? 1 : -1);
    };
    const auto any_ellipsoid = [&] {
        return Ellipsoid({any_coordinate(), any_coordinate(), any_coordinate()},
                         generator.rotation(), {any_length(), any_length(), any_length()});
    };
    const int count = kSanitized ? 200 : 1000;
    for (int i = 0; i < count; ++i) {
        const Ellipsoid a = any_ellipsoid();
        const Ellipsoid b = i % 3 == 0 ? a : any_ellipsoid();
        const Contact c = ellipsoid_ellipsoid_contact(a, b);
        ASSERT_FALSE(std::isnan(c.depth) || std::isnan(c.point.x) || std::isnan(c.point.y) ||
                     std::isnan(c.point.z))
            << describe(a, b);
        ASSERT_NEAR(glm::length(c.normal), 1.0, 1e-12) << describe(a, b);
        // The point is finite whenever both solids lie within the doubles' range (an extreme
        // point beyond it is infinite, as it should be).
        const auto inside_range = [](const Ellipsoid& e) {
            const glm::dvec3 m = glm::abs(e.center());
            return std::max({m.x, m.y, m.z}) + e.bounding_radius() <
                   std::numeric_limits<double>::max();
        };
        if (inside_range(a) && inside_range(b)) {
            ASSERT_TRUE(finite(c)) << describe(a, b);
        }
    }
}

TEST(EllipsoidPair, ShallowAndSeparatedPairsAreCertifiedWithoutSearch) {
    PairCaseGenerator generator(17);
    for (int i = 0; i < 1000; ++i) {
        const PairCase c = generator.make(i % 2 ? PairKind::grazing : PairKind::far);
        const detail::PairSolution s = detail::pair_solution(c.a, c.b);
        ASSERT_TRUE(s.path == detail::PairPath::separated ||
                    s.path == detail::PairPath::inscribed_balls)
            << describe(c);
        ASSERT_EQ(s.path == detail::PairPath::separated,
                  ellipsoid_ellipsoid_contact(c.a, c.b).depth < 0.0)
            << describe(c);
    }
}

// fuzz_ellipsoid_pair's -seed=1 finding (fuzz/seeds/fuzz_ellipsoid_pair/
// centred_needle_through_spheroid.seed): one centre, a 2 mm spheroid across a 27.8 m needle.
// h's minima lie in a valley 3.5e-5 rad wide about the circle orthogonal to the needle;
// the search ran out of evaluations along it and answered the saddle along the spheroid's
// long axis (3 * 2^-10) instead of the minimum across it (2^-9).
TEST(EllipsoidPair, CentredNeedleThroughASpheroidFindsTheValleyMinimum) {
    const Ellipsoid a({0.0, 0.0, 0.0},
                      glm::dquat(0x1.ffff0000bfff6p-9, 0.0, 0x1.ffff0000bfff6p-1, 0.0),
                      {0x1p-10, 0x1p-9, 0x1p-10});
    const Ellipsoid b({0.0, 0.0, 0.0}, glm::dquat(0.0, 0.0, 0.0, 1.0),
                      {0x1p-10, 0x1p-10, 0x1.bd04p+4});
    for (const bool swap : {false, true}) {
        const Contact got =
            swap ? ellipsoid_ellipsoid_contact(b, a) : ellipsoid_ellipsoid_contact(a, b);
        test::PairReference solver(swap ? b : a, swap ? a : b);
        const test::PairReferenceResult ref = solver.solve();
        EXPECT_NEAR(double(ref.depth), 0x1p-9, 1e-12);
        EXPECT_NEAR(got.depth, double(ref.depth), depth_tolerance(largest_axis(a, b)));
        EXPECT_NEAR(std::abs(got.normal.y), 0.0, 1e-6);
        EXPECT_NEAR(std::abs(got.normal.z), 0.0, 1e-6);
        // The search runs out of evaluations along the valley and says so: the answer (the
        // axes' descents') is right, but not proven; its lower bound is a true one.
        const detail::PairSolution solution = detail::pair_solution(swap ? b : a, swap ? a : b);
        EXPECT_EQ(solution.path, detail::PairPath::unproven);
        const double unit = got.depth / solution.depth;
        EXPECT_LE(solution.lower_bound * unit, double(ref.depth));
        EXPECT_LT(solution.lower_bound, solution.depth);
    }
}

TEST(EllipsoidPair, KnownAnswers) {
    const glm::dquat identity(1.0, 0.0, 0.0, 0.0);
    // Two boxes' worth of car bodies side by side along x, 0.1 m apart.
    const Ellipsoid a({0.0, 0.0, 0.0}, identity, {1.0, 0.5, 2.0});
    const Ellipsoid b({2.1, 0.0, 0.0}, identity, {1.0, 0.7, 2.5});
    const Contact apart = ellipsoid_ellipsoid_contact(a, b);
    EXPECT_NEAR(apart.depth, -0.1, 1e-15);
    EXPECT_EQ(apart.normal, glm::dvec3(-1.0, 0.0, 0.0));
    EXPECT_NEAR(glm::distance(apart.point, glm::dvec3(1.05, 0.0, 0.0)), 0.0, 1e-15);
    // Two flat ones stacked along z, overlapping by 0.1 m: pushing a down is the way out.
    const Ellipsoid low({0.0, 0.0, 0.0}, identity, {2.0, 2.0, 0.5});
    const Ellipsoid high({0.0, 0.0, 0.9}, identity, {2.0, 2.0, 0.5});
    const Contact overlap = ellipsoid_ellipsoid_contact(low, high);
    EXPECT_NEAR(overlap.depth, 0.1, 1e-15);
    EXPECT_NEAR(glm::distance(overlap.normal, glm::dvec3(0.0, 0.0, -1.0)), 0.0, 1e-15);
    EXPECT_NEAR(glm::distance(overlap.point, glm::dvec3(0.0, 0.0, 0.45)), 0.0, 1e-15);
    // One centre, the same shape turned a quarter about z: h is 1 + 0.5 along x and along y,
    // 4 along the common long axis z; the way out is x or y.
    const Ellipsoid d({0.0, 0.0, 0.0}, glm::angleAxis(1.5707963267948966, glm::dvec3(0, 0, 1)),
                      {1.0, 0.5, 2.0});
    const Contact crossed = ellipsoid_ellipsoid_contact(a, d);
    EXPECT_NEAR(crossed.depth, 1.5, 1e-12);
    EXPECT_NEAR(std::abs(crossed.normal.z), 0.0, 1e-6);
    EXPECT_NEAR(std::abs(crossed.normal.x) * std::abs(crossed.normal.y), 0.0, 1e-6);
}

}  // namespace
}  // namespace trackphys

namespace trackphys {
namespace {

// The rejection is a certificate: never false for a pair within reach, and it rejects
// most far pairs (all of them beyond their bounding spheres).
TEST(EllipsoidPair, MayTouchRejectsOnlyPairsBeyondReach) {
    PairCaseGenerator generator(18);
    int rejected_far = 0, far = 0;
    for (int k = 0; k < static_cast<int>(PairKind::count); ++k)
        for (int i = 0; i < 300; ++i) {
            const PairCase c = generator.make(static_cast<PairKind>(k));
            const double depth = ellipsoid_ellipsoid_contact(c.a, c.b).depth;
            for (const double reach : {0.0, 0.05, 0.5, 20.0}) {
                const bool may = ellipsoids_may_touch(c.a, c.b, reach);
                if (depth >= -reach) {
                    ASSERT_TRUE(may) << describe(c) << " reach " << reach;
                }
            }
            if (c.kind == PairKind::far) {
                ++far;
                rejected_far += !ellipsoids_may_touch(c.a, c.b, 0.5);
            }
        }
    EXPECT_EQ(rejected_far, far);
    const Ellipsoid a({0.0, 0.0, 0.0}, glm::dquat(1.0, 0.0, 0.0, 0.0), {2.0, 0.5, 0.5});
    // Beyond the centre-line gap but inside the bounding spheres: rejected by the second
    // certificate.
    const Ellipsoid b({0.0, 2.0, 0.0}, glm::dquat(1.0, 0.0, 0.0, 0.0), {2.0, 0.5, 0.5});
    EXPECT_FALSE(ellipsoids_may_touch(a, b, 0.5));
    EXPECT_TRUE(ellipsoids_may_touch(a, b, 1.0));
    EXPECT_TRUE(ellipsoids_may_touch(a, a, 0.0));
    EXPECT_TRUE(ellipsoids_may_touch(a, b, -1.0));
}

}  // namespace
}  // namespace trackphys
