#include "trackphys/geometry/ellipsoid_cull.hpp"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

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
