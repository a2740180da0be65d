#include "trackphys/geometry/ellipsoid_cull.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <span>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "geometry/ellipsoid_cull_list.hpp"
#include "support/contact_cases.hpp"
#include "trackphys/geometry/contact.hpp"

namespace trackphys {
namespace {

// The second cull is conservative: whenever the exact contact says the ellipsoid and the
// triangle overlap, the cull keeps the pair; and it does reject many pairs that miss.
TEST(EllipsoidCull, NeverRejectsAnOverlappingPair) {
    test::ContactCaseGenerator cases(4242);
    int overlapping = 0, rejected = 0;
    for (int i = 0; i < 60000; ++i) {
        const auto kind =
            static_cast<test::ContactKind>(i % static_cast<int>(test::ContactKind::count));
        const test::ContactCase c = cases.make(kind);
        if (c.triangle.is_degenerate()) continue;
        const NormalizedTriangle normalized(c.triangle);
        const bool kept = ellipsoid_may_touch(normalized, c.ellipsoid);
        const Contact contact = ellipsoid_triangle_contact(c.ellipsoid, c.triangle);
        if (contact.depth > 1e-9) {
            ++overlapping;
            ASSERT_TRUE(kept) << "case " << i << " (" << test::contact_kind_name(kind)
                              << ") overlaps by " << contact.depth << " m";
        } else if (!kept) {
            ++rejected;
        }
    }
    EXPECT_GT(overlapping, 10000);
    EXPECT_GT(rejected, 5000);
}

// Slivers 10 m long and 1e-6 to 1e-10 m high, which Triangle::is_degenerate keeps: a sphere
// that reaches past a vertex by d overlaps the triangle by at least d, since the vertex lies
// in the triangle. The cull must keep the pair and bound its depth by at least d. The vertex at the
// far end of the longest edge is where a frame normal tilted along that edge lies farthest
// off the frame's plane.
TEST(EllipsoidCull, NeverRejectsASphereReachingASliversVertex) {
    std::mt19937_64 rng(2024);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::normal_distribution<double> gauss;
    const auto random_direction = [&] {
        return glm::normalize(glm::dvec3(gauss(rng), gauss(rng), gauss(rng)));
    };
    const double radius = 0.3;
    int overlapping = 0;
    for (const double height : {1e-6, 1e-8, 1e-10}) {
        for (int i = 0; i < 20000; ++i) {
            const glm::dvec3 along = random_direction();
            const glm::dvec3 across = glm::normalize(glm::cross(along, random_direction()));
            const glm::dvec3 origin(100.0 * unit(rng), 100.0 * unit(rng), 10.0 * unit(rng));
            const Triangle sliver{origin, origin + 10.0 * along,
                                  origin + 10.0 * unit(rng) * along + height * across};
            ASSERT_FALSE(sliver.is_degenerate());
            // From either side, nearly along the plane's normal: there a plane through the
            // vertex is what the sphere first reaches, so an error in the plane shows whole.
            const glm::dvec3 plane_normal = glm::cross(along, across);
            const glm::dvec3 towards = glm::normalize((i % 2 == 0 ? 1.0 : -1.0) * plane_normal +
                                                      1e-4 * random_direction());
            const glm::dvec3& vertex = sliver[i % 3];
            const double reach = 1e-5 * unit(rng);
            const Ellipsoid sphere(vertex + (radius - reach) * towards, glm::dquat(1, 0, 0, 0),
                                   glm::dvec3(radius));
            // The overlap at the vertex, in long double from the rounded centre.
            long double distance2 = 0;
            for (int k = 0; k < 3; ++k) {
                const long double d = static_cast<long double>(sphere.center()[k]) - vertex[k];
                distance2 += d * d;
            }
            const double overlap = double(radius - std::sqrt(distance2));
            if (overlap < 1e-12) continue;
            ++overlapping;
            const double bound = ellipsoid_depth_bound(NormalizedTriangle(sliver), sphere);
            ASSERT_GE(bound, overlap - 1e-12)
                << "sliver " << height << " m, case " << i << ", vertex " << i % 3;
        }
    }
    EXPECT_GT(overlapping, 50000);
}

// Any direction bounds the depth from above, and the contact's own normal gives the depth
// itself: the bound the world's exact phase skips neighbours with.
TEST(EllipsoidCull, DepthBoundAlongAnyDirectionHoldsAndIsTightAtTheContactNormal) {
    test::ContactCaseGenerator cases(977);
    std::mt19937_64 rng(31);
    std::normal_distribution<double> gauss;
    int tested = 0, tight = 0;
    for (int i = 0; i < 20000; ++i) {
        const auto kind =
            static_cast<test::ContactKind>(i % static_cast<int>(test::ContactKind::count));
        const test::ContactCase c = cases.make(kind);
        if (c.triangle.is_degenerate()) continue;
        ++tested;
        const NormalizedTriangle frame(c.triangle);
        const Contact contact = ellipsoid_triangle_contact(c.ellipsoid, c.triangle);
        const double scale =
            1e-12 * (1.0 + c.ellipsoid.sorted_radii().x + glm::length(c.ellipsoid.center()) +
                     glm::length(c.triangle[0]));
        const glm::dvec3 u = glm::normalize(glm::dvec3(gauss(rng), gauss(rng), gauss(rng)));
        ASSERT_GE(depth_bound_along(frame, c.ellipsoid, u, support_extent(c.ellipsoid, u)),
                  contact.depth - scale)
            << "case " << i << " (" << test::contact_kind_name(kind) << ")";
        const double at_normal = depth_bound_along(frame, c.ellipsoid, contact.normal,
                                                   support_extent(c.ellipsoid, contact.normal));
        ASSERT_GE(at_normal, contact.depth - scale) << "case " << i;
        tight += at_normal - contact.depth < 1e-9 * (1.0 + std::abs(contact.depth));
    }
    EXPECT_GT(tight, 0.95 * tested);
}

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// The lanes' bounds as World's cull computes them: four lanes in code compiled for AVX2.
std::array<double, 2> lane_bounds(const Ellipsoid& e, const NormalizedTriangle* const (&t)[2]) {
    return detail::EllipsoidCull<2>(e).depth_bounds(t);
}
[[gnu::target("avx2")]] std::array<double, 4> lane_bounds(const Ellipsoid& e,
                                                          const NormalizedTriangle* const (&t)[4]) {
    return detail::EllipsoidCull<4>(e).depth_bounds(t);
}

// The N-lane cull is the scalar one bit for bit, in every lane, on every kind of case
// (separated, touching, deep, slivers): results must not move with it. Each case's own
// triangle, seldom far from its ellipsoid, goes through every lane beside N - 1 others.
template <int N>
void expect_lanes_give_the_scalar_bounds(std::uint64_t seed) {
    test::ContactCaseGenerator cases(seed);
    int kept = 0, rejected = 0;
    for (int i = 0; i < 40000; ++i) {
        const auto kind =
            static_cast<test::ContactKind>(i % static_cast<int>(test::ContactKind::count));
        const test::ContactCase c = cases.make(kind);
        if (c.triangle.is_degenerate()) continue;
        std::vector<NormalizedTriangle> frames{NormalizedTriangle(c.triangle)};
        while (frames.size() < N) {
            const Triangle other = cases.make(kind).triangle;
            if (!other.is_degenerate()) frames.emplace_back(other);
        }
        for (int turn = 0; turn < N; ++turn) {
            const NormalizedTriangle* lanes[N];
            for (int k = 0; k < N; ++k) lanes[k] = &frames[(k + turn) % N];
            const std::array<double, N> bounds = lane_bounds(c.ellipsoid, lanes);
            for (int k = 0; k < N; ++k) {
                const double scalar = ellipsoid_depth_bound(*lanes[k], c.ellipsoid);
                ASSERT_TRUE(same_bits(bounds[k], scalar))
                    << N << " lanes, case " << i << " (" << test::contact_kind_name(kind)
                    << "), lane " << k << ": " << bounds[k] << " against " << scalar;
            }
        }
        (ellipsoid_depth_bound(frames[0], c.ellipsoid) > 0.0 ? kept : rejected) += 1;
    }
    EXPECT_GT(kept, 5000);
    EXPECT_GT(rejected, 5000);
}

TEST(EllipsoidCull, TwoLanesGiveTheScalarBoundsBitForBit) {
    expect_lanes_give_the_scalar_bounds<2>(8128);
}

TEST(EllipsoidCull, FourLanesGiveTheScalarBoundsBitForBit) {
    if (!detail::cpu_has_avx2()) GTEST_SKIP() << "this CPU has no AVX2: four lanes not tested";
    expect_lanes_give_the_scalar_bounds<4>(8128);
}

// A listed triangle as the mid phase gives it, with its place in the list.
struct Listed {
    std::size_t index;
    const NormalizedTriangle* triangle;
};

// World's cull of one ellipsoid's list keeps exactly the triangles whose scalar bound is
// above zero, with that bound, in list order, at every list length: whole blocks of lanes
// and every tail, which repeats its last triangle in the lanes left over.
template <class Cull>
void expect_the_list_culled_as_scalar(Cull cull) {
    test::ContactCaseGenerator cases(2718);
    int kept_total = 0, rejected_total = 0;
    for (int i = 0; i < 6000; ++i) {
        const auto kind =
            static_cast<test::ContactKind>(i % static_cast<int>(test::ContactKind::count));
        const test::ContactCase c = cases.make(kind);
        if (c.triangle.is_degenerate()) continue;  // a kind that never gives a triangle
        // Other cases' triangles, moved to this case's ellipsoid: some kept, some not.
        std::vector<NormalizedTriangle> frames;
        const std::size_t length = static_cast<std::size_t>(i) / 17 % 12;
        while (frames.size() < length) {
            const test::ContactCase other = cases.make(kind);
            const glm::dvec3 shift = c.ellipsoid.center() - other.ellipsoid.center();
            const Triangle near{other.triangle[0] + shift, other.triangle[1] + shift,
                                other.triangle[2] + shift};
            if (!near.is_degenerate()) frames.emplace_back(near);
        }
        std::vector<Listed> listed;
        for (std::size_t k = 0; k < frames.size(); ++k) listed.push_back({k, &frames[k]});
        std::vector<std::pair<std::size_t, double>> kept;
        const auto keep = [&](const Listed& l, double bound) { kept.emplace_back(l.index, bound); };
        cull(c.ellipsoid, std::span<const Listed>(listed), keep);
        std::size_t next = 0;
        for (std::size_t k = 0; k < frames.size(); ++k) {
            const double scalar = ellipsoid_depth_bound(frames[k], c.ellipsoid);
            if (!(scalar > 0.0)) {
                ++rejected_total;
                continue;
            }
            ++kept_total;
            ASSERT_LT(next, kept.size()) << "list of " << length << ": " << k << " dropped";
            ASSERT_EQ(kept[next].first, k) << "list of " << length;
            ASSERT_TRUE(same_bits(kept[next].second, scalar)) << "list of " << length;
            ++next;
        }
        ASSERT_EQ(next, kept.size()) << "list of " << length << ": a triangle kept twice";
    }
    EXPECT_GT(kept_total, 3000);
    EXPECT_GT(rejected_total, 3000);
}

TEST(EllipsoidCull, TwoLanesCullAListAsTheScalarBound) {
    expect_the_list_culled_as_scalar(
        [](const Ellipsoid& e, std::span<const Listed> listed, const auto& keep) {
            detail::cull_listed<2>(e, listed, keep);
        });
}

TEST(EllipsoidCull, FourLanesCullAListAsTheScalarBound) {
    if (!detail::cpu_has_avx2()) GTEST_SKIP() << "this CPU has no AVX2: four lanes not tested";
    expect_the_list_culled_as_scalar(
        [](const Ellipsoid& e, std::span<const Listed> listed, const auto& keep) {
            detail::cull_listed_avx2(e, listed, keep);
        });
}

TEST(EllipsoidCull, SupportExtentIsTheHalfWidthAlongADirection) {
    const Ellipsoid wheel({0, 0, 0}, glm::dquat(1, 0, 0, 0), {0.15, 0.35, 0.35});
    EXPECT_NEAR(support_extent(wheel, {1, 0, 0}), 0.15, 1e-15);
    EXPECT_NEAR(support_extent(wheel, {0, 1, 0}), 0.35, 1e-15);
    const glm::dvec3 diagonal = glm::normalize(glm::dvec3(1, 1, 0));
    EXPECT_NEAR(support_extent(wheel, diagonal), std::sqrt(0.5 * (0.15 * 0.15 + 0.35 * 0.35)),
                1e-15);
}

}  // namespace
}  // namespace trackphys
