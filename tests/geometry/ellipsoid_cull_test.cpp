#include "trackphys/geometry/ellipsoid_cull.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "geometry/ellipsoid_cull_lanes.hpp"
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

// The two-lane cull World runs is the scalar one bit for bit, in either lane, on every
// kind of case (separated, touching, deep, slivers): results must not move with it.
TEST(EllipsoidCull, TwoLanesGiveTheScalarBoundsBitForBit) {
    test::ContactCaseGenerator cases(8128);
    const auto same_bits = [](double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; };
    int kept = 0, rejected = 0;
    for (int i = 0; i < 40000; ++i) {
        const auto kind =
            static_cast<test::ContactKind>(i % static_cast<int>(test::ContactKind::count));
        const test::ContactCase c = cases.make(kind);
        const test::ContactCase other = cases.make(kind);
        if (c.triangle.is_degenerate() || other.triangle.is_degenerate()) continue;
        const NormalizedTriangle t(c.triangle);
        const NormalizedTriangle u(other.triangle);
        const std::array<double, 2> bounds = detail::EllipsoidCull(c.ellipsoid).depth_bounds(t, u);
        const double scalar = ellipsoid_depth_bound(t, c.ellipsoid);
        ASSERT_TRUE(same_bits(bounds[0], scalar))
            << "case " << i << " (" << test::contact_kind_name(kind) << "): " << bounds[0]
            << " against " << scalar;
        ASSERT_TRUE(same_bits(bounds[1], ellipsoid_depth_bound(u, c.ellipsoid))) << "case " << i;
        // The case's own triangle in the second lane too: u is seldom near c's ellipsoid.
        const std::array<double, 2> swapped = detail::EllipsoidCull(c.ellipsoid).depth_bounds(u, t);
        ASSERT_TRUE(same_bits(swapped[1], scalar)) << "case " << i << " in the second lane";
        ASSERT_TRUE(same_bits(swapped[0], bounds[1])) << "case " << i;
        (scalar > -std::numeric_limits<double>::infinity() ? kept : rejected) += 1;
    }
    EXPECT_GT(kept, 5000);
    EXPECT_GT(rejected, 5000);
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
