// The batched ellipsoid-ellipsoid contact against the single call, bit for bit, and the
// lanes of its common path against solve_pair. Run in four lanes on an AVX2 machine and again
// in two (twolanes., TRACKPHYS_LANES=2).

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <random>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "geometry/ellipsoid_pair_kernel.hpp"
#include "support/ellipsoid_pair_cases.hpp"
#include "support/same_bits.hpp"
#include "trackphys/geometry/ellipsoid_pair.hpp"

namespace trackphys {
namespace {

using test::PairCase;
using test::PairCaseGenerator;
using test::PairKind;

constexpr int kPerFamily = test::kSanitized ? 150 : 1000;

std::uint64_t bits(double v) { return std::bit_cast<std::uint64_t>(v); }

using test::same_bits;

/// Every contact of the batch against the single call, with the pair's index on failure.
void expect_batch_is_single(const std::vector<Ellipsoid>& a, const std::vector<Ellipsoid>& b,
                            const std::string& what) {
    std::vector<Contact> batch(a.size());
    ellipsoid_ellipsoid_contacts(a, b, batch);
    for (std::size_t i = 0; i < a.size(); ++i) {
        const Contact single = ellipsoid_ellipsoid_contact(a[i], b[i]);
        ASSERT_EQ(bits(batch[i].depth), bits(single.depth)) << what << " pair " << i;
        ASSERT_TRUE(same_bits(batch[i].normal, single.normal)) << what << " pair " << i;
        ASSERT_TRUE(same_bits(batch[i].point, single.point)) << what << " pair " << i;
    }
}

/// The pairs in batches of each size (the lanes' block of four and its neighbours, a car
/// pair's eight, the whole list), in order and shuffled.
void expect_every_batching_is_single(std::vector<PairCase> cases, const std::string& what) {
    std::mt19937_64 rng(7);
    for (const bool shuffled : {false, true}) {
        if (shuffled) std::shuffle(cases.begin(), cases.end(), rng);
        for (const std::size_t size :
             {std::size_t(0), std::size_t(1), std::size_t(3), std::size_t(4), std::size_t(5),
              std::size_t(7), std::size_t(8), std::size_t(9), cases.size()}) {
            if (size == 0) {
                expect_batch_is_single({}, {}, what + ", an empty batch");
                continue;
            }
            for (std::size_t start = 0; start < cases.size(); start += size) {
                const std::size_t count = std::min(size, cases.size() - start);
                std::vector<Ellipsoid> a, b;
                for (std::size_t i = start; i < start + count; ++i) {
                    a.push_back(cases[i].a);
                    b.push_back(cases[i].b);
                }
                expect_batch_is_single(a, b,
                                       what + (shuffled ? " shuffled" : "") + ", batches of " +
                                           std::to_string(size) + " from " + std::to_string(start));
                if (::testing::Test::HasFatalFailure()) return;
            }
        }
    }
}

std::vector<PairCase> family(PairKind kind, int count, std::uint64_t seed) {
    PairCaseGenerator generator(seed);
    std::vector<PairCase> cases;
    for (int i = 0; i < count; ++i) cases.push_back(generator.make(kind));
    return cases;
}

TEST(EllipsoidPairBatch, EqualsTheSingleCallOnEveryFamily) {
    for (int k = 0; k < static_cast<int>(PairKind::count); ++k) {
        const auto kind = static_cast<PairKind>(k);
        expect_every_batching_is_single(family(kind, kPerFamily, 1500 + k),
                                        test::pair_kind_name(kind));
        if (HasFatalFailure()) return;
    }
}

TEST(EllipsoidPairBatch, EqualsTheSingleCallOnHostilePairs) {
    PairCaseGenerator generator(1515);
    std::vector<PairCase> cases;
    const auto add = [&](const Ellipsoid& a, const Ellipsoid& b) {
        cases.push_back({a, b, PairKind::car_like});
    };
    const double huge = std::numeric_limits<double>::max();
    for (int i = 0; i < 40; ++i) {
        const glm::dquat q = generator.rotation();
        const Ellipsoid car(generator.unit_vector() * generator.uniform(0.0, 3.0), q,
                            generator.car_axes());
        // Far field, both ways round.
        const Ellipsoid far(generator.unit_vector() * std::ldexp(1.0, 520 + 11 * i),
                            generator.rotation(), generator.car_axes());
        add(car, far);
        add(far, car);
        // Coincident centres, identical, and a needle through a disc.
        add(car, Ellipsoid(car.center(), generator.rotation(), generator.car_axes()));
        add(car, car);
        add(Ellipsoid(car.center(), q, {2.0, 1e-4, 1e-4}),
            Ellipsoid(car.center() + generator.unit_vector() * 0.1, generator.rotation(),
                      {1.0, 1.0, 1e-3}));
        // Car-like pairs scaled by 2^-500..2^500.
        const PairCase c = generator.make(PairKind::car_like);
        const double s = std::ldexp(1.0, -500 + 25 * i);
        const auto scaled = [s](const Ellipsoid& e) {
            return Ellipsoid(e.center() * s, e.orientation(), e.semi_axes() * s);
        };
        add(scaled(c.a), scaled(c.b));
        // Finite extremes: lengths 1e-300..1e300, coordinates up to the largest double.
        const auto any_length = [&] { return std::pow(10.0, generator.uniform(-300.0, 300.0)); };
        const auto any_coordinate = [&] {
            const double x = generator.uniform(0, 1);
            if (x < 0.1) return 0.0;
            if (x < 0.15) return huge * (x < 0.125 ? 1 : -1);
            return any_length() * (generator.uniform(0, 1) < 0.5 ? 1 : -1);
        };
        const auto any_ellipsoid = [&] {
            return Ellipsoid({any_coordinate(), any_coordinate(), any_coordinate()},
                             generator.rotation(), {any_length(), any_length(), any_length()});
        };
        const Ellipsoid e = any_ellipsoid();
        add(e, i % 3 == 0 ? e : any_ellipsoid());
    }
    expect_every_batching_is_single(cases, "hostile");
}

TEST(EllipsoidPairBatch, SpansOfDifferentSizesThrow) {
    const Ellipsoid e({0.0, 0.0, 0.0}, glm::dquat(1.0, 0.0, 0.0, 0.0), {1.0, 1.0, 1.0});
    std::vector<Ellipsoid> two{e, e}, one{e};
    std::vector<Contact> contacts_two(2), contacts_one(1);
    EXPECT_THROW(ellipsoid_ellipsoid_contacts(two, one, contacts_two), std::invalid_argument);
    EXPECT_THROW(ellipsoid_ellipsoid_contacts(one, two, contacts_two), std::invalid_argument);
    EXPECT_THROW(ellipsoid_ellipsoid_contacts(two, two, contacts_one), std::invalid_argument);
    EXPECT_NO_THROW(ellipsoid_ellipsoid_contacts(two, two, contacts_two));
}

/// Solves the frames on the common path and checks that what the lanes keep is solve_pair's
/// answer, path and evaluations included; returns how many frames they kept.
std::size_t expect_kept_frames_are_solve_pairs(const std::vector<detail::PairFrame>& frames,
                                               const std::string& what) {
    std::vector<detail::PairSolution> solutions(frames.size());
    std::unique_ptr<bool[]> kept(new bool[frames.size()]);
    detail::solve_pairs_on_common_path(frames, solutions, std::span(kept.get(), frames.size()));
    std::size_t count = 0;
    for (std::size_t i = 0; i < frames.size(); ++i) {
        if (!kept[i]) continue;
        ++count;
        const detail::PairSolution want = detail::solve_pair(frames[i]);
        const detail::PairSolution& got = solutions[i];
        const std::string frame = what + " frame " + std::to_string(i);
        EXPECT_EQ(bits(got.depth), bits(want.depth)) << frame;
        EXPECT_TRUE(same_bits(got.n, want.n)) << frame;
        EXPECT_TRUE(same_bits(got.extreme_a, want.extreme_a)) << frame;
        EXPECT_TRUE(same_bits(got.extreme_b, want.extreme_b)) << frame;
        EXPECT_EQ(got.path, want.path) << frame;
        EXPECT_EQ(got.evaluations, want.evaluations) << frame;
        EXPECT_EQ(bits(got.lower_bound), bits(want.lower_bound)) << frame;
        if (::testing::Test::HasFailure()) break;
    }
    return count;
}

/// The lanes keep most car-like pairs (a lane that always gave up would pass the tests
/// above), and what they keep is solve_pair's answer, path and evaluations included.
TEST(EllipsoidPairBatch, LanesKeepTheCommonPathWithSolvePairsBits) {
    for (const PairKind kind : {PairKind::car_like, PairKind::grazing, PairKind::far,
                                PairKind::spheres, PairKind::sphere_ellipsoid}) {
        std::vector<detail::PairFrame> frames;
        for (const PairCase& c : family(kind, kPerFamily, 1600)) {
            detail::PairFrame frame;
            if (detail::pair_frame(c.a, c.b, frame)) frames.push_back(frame);
        }
        const std::string what = test::pair_kind_name(kind);
        const std::size_t kept = expect_kept_frames_are_solve_pairs(frames, what);
        EXPECT_GT(double(kept), 0.9 * double(frames.size())) << what;
    }
}

/// Car-like pairs 2^5 to 2^64 m apart: the first guess's length grows as a high power of the
/// distance, past 2^-60..2^60, where the lanes scale it back by a power of two as solve_pair
/// does, and past 2^-600..2^600 (from about 2^29 m), where solve_pair starts on the centre
/// line and the lanes drop the frame. Up to 2^28 m every frame is kept (a lane that did not
/// scale the guess back would overflow there), and every kept one is solve_pair's.
TEST(EllipsoidPairBatch, LanesScaleAFarPairsFirstGuessAsSolvePairDoes) {
    PairCaseGenerator generator(1700);
    std::vector<detail::PairFrame> scaled, beyond;
    for (int exponent = 5; exponent <= 64; ++exponent)
        for (int j = 0; j < 4; ++j) {
            const PairCase c = generator.make(PairKind::car_like);
            const Ellipsoid b(c.a.center() + generator.unit_vector() * std::ldexp(1.0, exponent),
                              c.b.orientation(), c.b.semi_axes());
            detail::PairFrame frame;
            ASSERT_TRUE(detail::pair_frame(c.a, b, frame));
            (exponent <= 28 ? scaled : beyond).push_back(frame);
        }
    EXPECT_EQ(expect_kept_frames_are_solve_pairs(scaled, "2^5..2^28 m apart"), scaled.size());
    expect_kept_frames_are_solve_pairs(beyond, "2^29..2^64 m apart");
}

}  // namespace
}  // namespace trackphys
