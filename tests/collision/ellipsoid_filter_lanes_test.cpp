#include "collision/ellipsoid_filter_lanes.hpp"

#include <cstdint>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "core/cpu_features.hpp"
#include "support/contact_cases.hpp"

namespace trackphys {
namespace {

using collision_detail::EllipsoidFilterLanes;
using collision_detail::EllipsoidShape;

// The lanes' decisions as the plane tree takes them: four lanes in code compiled for AVX2.
// Lane k's answer: touched, or undecided and the exact test says so.
template <int N>
unsigned lanes_touched(const EllipsoidShape& shape, const NormalizedTriangle* const (&t)[N],
                       typename EllipsoidFilterLanes<N>::Decisions decided) {
    unsigned touched = decided.touched;
    for (int k = 0; k < N; ++k)
        if ((decided.undecided >> k & 1u) != 0 && shape.touches_exactly(*t[k])) touched |= 1u << k;
    return touched;
}
EllipsoidFilterLanes<2>::Decisions decide(const EllipsoidShape& shape,
                                          const NormalizedTriangle* const (&t)[2]) {
    return EllipsoidFilterLanes<2>(shape).decide(t);
}
[[gnu::target("avx2")]] EllipsoidFilterLanes<4>::Decisions decide(
    const EllipsoidShape& shape, const NormalizedTriangle* const (&t)[4]) {
    return EllipsoidFilterLanes<4>(shape).decide(t);
}

// Every lane answers as EllipsoidShape::touches does, on every kind of case (apart,
// touching, deep, slivers), swept or not, with and without a margin: the plane tree's
// answers must not move with the lanes. Each case's own triangle, seldom far from its
// ellipsoid, goes through every lane beside N - 1 others moved to its ellipsoid; each of
// the lanes' three answers (rejected, surely touched, left to the exact test) is seen, both
// ways for the last.
template <int N>
void expect_lanes_touch_as_the_scalar_filter(std::uint64_t seed) {
    test::ContactCaseGenerator cases(seed);
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> sym(-1.0, 1.0), unit(0.0, 1.0);
    int rejected = 0, sure = 0, exact_touched = 0, exact_missed = 0;
    for (int i = 0; i < 30000; ++i) {
        const auto kind =
            static_cast<test::ContactKind>(i % static_cast<int>(test::ContactKind::count));
        const test::ContactCase c = cases.make(kind);
        if (c.triangle.is_degenerate()) continue;
        std::vector<NormalizedTriangle> frames{NormalizedTriangle(c.triangle)};
        while (frames.size() < N) {
            const test::ContactCase other = cases.make(kind);
            const glm::dvec3 shift = c.ellipsoid.center() - other.ellipsoid.center();
            const Triangle near{other.triangle[0] + shift, other.triangle[1] + shift,
                                other.triangle[2] + shift};
            if (!near.is_degenerate()) frames.emplace_back(near);
        }
        const double sweep = i % 3 == 0 ? 0.0 : 0.5 * unit(rng);
        const glm::dvec3 end =
            c.ellipsoid.center() + sweep * glm::dvec3(sym(rng), sym(rng), sym(rng));
        const EllipsoidShape shape(c.ellipsoid, end, i % 2 == 0 ? 0.0 : 0.05 * unit(rng));
        for (int turn = 0; turn < N; ++turn) {
            const NormalizedTriangle* lanes[N];
            for (int k = 0; k < N; ++k) lanes[k] = &frames[(k + turn) % N];
            const auto decided = decide(shape, lanes);
            const unsigned touched = lanes_touched<N>(shape, lanes, decided);
            for (int k = 0; k < N; ++k) {
                const bool scalar = shape.touches(*lanes[k]);
                ASSERT_EQ((touched >> k & 1u) != 0, scalar)
                    << N << " lanes, case " << i << " (" << test::contact_kind_name(kind)
                    << "), lane " << k;
                if (turn != 0) continue;
                if ((decided.touched >> k & 1u) != 0)
                    ++sure;
                else if ((decided.undecided >> k & 1u) == 0)
                    ++rejected;
                else
                    ++(scalar ? exact_touched : exact_missed);
            }
        }
    }
    EXPECT_GT(rejected, 5000);
    EXPECT_GT(sure, 5000);
    EXPECT_GT(exact_touched, 500);
    EXPECT_GT(exact_missed, 500);
}

TEST(EllipsoidFilterLanes, TwoLanesTouchAsTheScalarFilter) {
    expect_lanes_touch_as_the_scalar_filter<2>(6174);
}

TEST(EllipsoidFilterLanes, FourLanesTouchAsTheScalarFilter) {
    if (!detail::cpu_has_avx2()) GTEST_SKIP() << "this CPU has no AVX2: four lanes not tested";
    expect_lanes_touch_as_the_scalar_filter<4>(6174);
}

}  // namespace
}  // namespace trackphys
