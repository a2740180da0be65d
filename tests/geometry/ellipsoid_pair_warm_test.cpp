// ellipsoid_ellipsoid_contact(a, b, previous_normal), the call started from an earlier
// contact's normal: the cold call's contract from every start, its symmetry, and that a
// good start saves evaluations.

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
#include <glm/gtc/quaternion.hpp>

#include "geometry/ellipsoid_pair_kernel.hpp"
#include "support/ellipsoid_pair_cases.hpp"
#include "support/ellipsoid_pair_contract.hpp"
#include "support/ellipsoid_pair_reference.hpp"
#include "trackphys/geometry/ellipsoid_pair.hpp"

namespace trackphys {
namespace {

using test::describe;
using test::PairCase;
using test::PairCaseGenerator;
using test::PairKind;

using test::kSanitized;
constexpr int kPairsPerKind = kSanitized ? 40 : 300;

constexpr double kInfinity = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// n turned by `angle` rad about a direction orthogonal to it drawn from the generator.
glm::dvec3 turned(const glm::dvec3& n, double angle, PairCaseGenerator& generator) {
    const glm::dvec3 axis = glm::normalize(glm::cross(n, generator.unit_vector()));
    return glm::angleAxis(angle, axis) * n;
}

struct Start {
    std::string name;
    glm::dvec3 normal;
};

/// The starts every pair is tried from: the cold contact's normal turned a little, a lot
/// and the wrong way; hostile ones; and the pair's contact one sub-step earlier.
std::vector<Start> starts(const PairCase& c, const glm::dvec3& cold, PairCaseGenerator& generator) {
    const PairCase before = generator.earlier(c);
    return {{"turned 1e-6", turned(cold, 1e-6, generator)},
            {"turned 1e-3", turned(cold, 1e-3, generator)},
            {"turned 0.1", turned(cold, 0.1, generator)},
            {"turned pi", -cold},
            {"zero", glm::dvec3(0.0)},
            {"NaN", glm::dvec3(kNaN, 0.0, 1.0)},
            {"infinite", glm::dvec3(0.0, kInfinity, 1.0)},
            {"a sub-step earlier", ellipsoid_ellipsoid_contact(before.a, before.b).normal}};
}

bool certified_without_search(const detail::PairSolution& s) {
    return s.path == detail::PairPath::separated || s.path == detail::PairPath::inscribed_balls;
}

TEST(EllipsoidPairWarm, MatchesTheLongDoubleReferenceFromEveryStart) {
    PairCaseGenerator generator(20261128);
    std::map<std::string, test::KindStats> stats;
    for (int k = 0; k < static_cast<int>(PairKind::count); ++k)
        for (int i = 0; i < kPairsPerKind; ++i) {
            const PairCase c = generator.make(static_cast<PairKind>(k));
            test::PairReference solver(c.a, c.b);
            const test::PairReferenceResult ref = solver.solve();
            const glm::dvec3 cold = ellipsoid_ellipsoid_contact(c.a, c.b).normal;
            for (const Start& start : starts(c, cold, generator)) {
                const Contact got = ellipsoid_ellipsoid_contact(c.a, c.b, start.normal);
                test::check_contract(c, got, ref, stats[start.name], " from " + start.name);
                if (HasFatalFailure()) return;
            }
        }
    std::printf("start               cases  unique  max|depth err|  max angle  max point err\n");
    for (const auto& [name, s] : stats)
        std::printf("%-18s %6ld  %6ld  %13.3g  %9.3g  %13.3g\n", name.c_str(), s.cases, s.unique,
                    s.depth_error, s.angle_error, s.point_error);
}

TEST(EllipsoidPairWarm, SwappingTheArgumentsAndTheStartNegatesTheNormalBitForBit) {
    PairCaseGenerator generator(21);
    for (int k = 0; k < static_cast<int>(PairKind::count); ++k)
        for (int i = 0; i < 100; ++i) {
            const PairCase c = generator.make(static_cast<PairKind>(k));
            const glm::dvec3 cold = ellipsoid_ellipsoid_contact(c.a, c.b).normal;
            for (const Start& start : starts(c, cold, generator)) {
                const Contact ab = ellipsoid_ellipsoid_contact(c.a, c.b, start.normal);
                const Contact ba = ellipsoid_ellipsoid_contact(c.b, c.a, -start.normal);
                ASSERT_EQ(std::bit_cast<std::uint64_t>(ab.depth),
                          std::bit_cast<std::uint64_t>(ba.depth))
                    << describe(c) << " from " << start.name;
                for (int j = 0; j < 3; ++j) {
                    ASSERT_EQ(std::bit_cast<std::uint64_t>(ab.normal[j]),
                              std::bit_cast<std::uint64_t>(-ba.normal[j]))
                        << describe(c) << " from " << start.name;
                    ASSERT_EQ(std::bit_cast<std::uint64_t>(ab.point[j]),
                              std::bit_cast<std::uint64_t>(ba.point[j]))
                        << describe(c) << " from " << start.name;
                }
            }
        }
}

// From the exact minimiser the descent's first Newton step is below its stop: one
// evaluation, where the cold call takes two or more from its first guess.
TEST(EllipsoidPairWarm, StartingAtTheMinimiserTakesFewerEvaluations) {
    PairCaseGenerator generator(22);
    int certified = 0;
    for (int i = 0; i < 1000; ++i) {
        const PairCase c = generator.make(PairKind::car_like);
        const detail::PairSolution cold = detail::pair_solution(c.a, c.b);
        if (!certified_without_search(cold)) continue;
        ++certified;
        const glm::dvec3 normal = ellipsoid_ellipsoid_contact(c.a, c.b).normal;
        const detail::PairSolution warm = detail::pair_solution(c.a, c.b, normal);
        ASSERT_EQ(warm.path, cold.path) << describe(c);
        ASSERT_LT(warm.evaluations, cold.evaluations) << describe(c);
    }
    EXPECT_GT(certified, 900);
}

// The start is a direction: scaled by any finite factor it takes the same path and as many
// evaluations (the call brings its length into the evaluation's range first).
TEST(EllipsoidPairWarm, AStartsLengthChangesNothing) {
    PairCaseGenerator generator(25);
    int certified = 0;
    for (int i = 0; i < 200; ++i) {
        const PairCase c = generator.make(PairKind::car_like);
        const glm::dvec3 normal = ellipsoid_ellipsoid_contact(c.a, c.b).normal;
        const detail::PairSolution unit = detail::pair_solution(c.a, c.b, normal);
        if (!certified_without_search(unit)) continue;
        ++certified;
        for (const double scale : {0x1p-1000, 1e-300, 0x1p-200, 0x1p-40, 0x1p40, 0x1p200, 1e300}) {
            const detail::PairSolution scaled = detail::pair_solution(c.a, c.b, normal * scale);
            ASSERT_EQ(scaled.path, unit.path) << describe(c) << " scaled by " << scale;
            ASSERT_EQ(scaled.evaluations, unit.evaluations)
                << describe(c) << " scaled by " << scale;
        }
    }
    EXPECT_GT(certified, 180);
}

// A start that is not certified leaves the answer to the cold call's path: the same bits.
TEST(EllipsoidPairWarm, AnUncertifiedStartGivesTheColdAnswerBitForBit) {
    PairCaseGenerator generator(23);
    int searched = 0;
    for (int i = 0; i < 200; ++i) {
        const PairCase c = generator.make(PairKind::deep);
        const glm::dvec3 start = generator.unit_vector();
        if (detail::pair_solution(c.a, c.b, start).path != detail::PairPath::searched) continue;
        ++searched;
        const Contact cold = ellipsoid_ellipsoid_contact(c.a, c.b);
        const Contact warm = ellipsoid_ellipsoid_contact(c.a, c.b, start);
        ASSERT_EQ(std::bit_cast<std::uint64_t>(warm.depth),
                  std::bit_cast<std::uint64_t>(cold.depth))
            << describe(c);
        ASSERT_EQ(warm.normal, cold.normal) << describe(c);
        ASSERT_EQ(warm.point, cold.point) << describe(c);
    }
    EXPECT_GT(searched, 100);
}

TEST(EllipsoidPairWarm, NoFiniteInputAndNoStartMakesNaN) {
    PairCaseGenerator generator(24);
    const auto any_length = [&] { return std::pow(10.0, generator.uniform(-300.0, 300.0)); };
    const auto any_coordinate = [&] {
        const double x = generator.uniform(0, 1);
        if (x < 0.1) return 0.0;
        if (x < 0.15) return std::numeric_limits<double>::max() * (x < 0.125 ? 1 : -1);
        if (x < 0.2) return std::numeric_limits<double>::denorm_min() * (x < 0.175 ? 1 : -1);
        return any_length() * (generator.uniform(0, 1) < 0.5 ? 1 : -1);
    };
    const auto any_ellipsoid = [&] {
        return Ellipsoid({any_coordinate(), any_coordinate(), any_coordinate()},
                         generator.rotation(), {any_length(), any_length(), any_length()});
    };
    const auto any_start = [&] {
        const double x = generator.uniform(0, 1);
        if (x < 0.1) return glm::dvec3(kNaN, any_coordinate(), any_coordinate());
        if (x < 0.2) return glm::dvec3(any_coordinate(), -kInfinity, any_coordinate());
        return glm::dvec3(any_coordinate(), any_coordinate(), any_coordinate());
    };
    const int count = kSanitized ? 200 : 2000;
    for (int i = 0; i < count; ++i) {
        const PairCase c = i % 2 ? generator.make(static_cast<PairKind>(i % int(PairKind::count)))
                                 : PairCase{any_ellipsoid(), any_ellipsoid(), PairKind::count};
        const glm::dvec3 start = any_start();
        const Contact got = ellipsoid_ellipsoid_contact(c.a, c.b, start);
        ASSERT_FALSE(std::isnan(got.depth) || std::isnan(got.point.x) || std::isnan(got.point.y) ||
                     std::isnan(got.point.z))
            << test::describe(c.a, c.b) << " from " << start.x << " " << start.y << " " << start.z;
        ASSERT_NEAR(glm::length(got.normal), 1.0, 1e-12) << test::describe(c.a, c.b);
    }
}

}  // namespace
}  // namespace trackphys
