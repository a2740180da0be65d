#include "trackphys/geometry/triangle.hpp"

#include <algorithm>
#include <array>
#include <random>

#include <gtest/gtest.h>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

namespace trackphys {
namespace {

TEST(Triangle, NormalFollowsCounterClockwiseWinding) {
    const Triangle t({0, 0, 0}, {1, 0, 0}, {0, 0, -1});
    EXPECT_EQ(t.normal(), glm::dvec3(0, 1, 0));
    EXPECT_DOUBLE_EQ(t.area(), 0.5);
    const Triangle flipped({0, 0, 0}, {0, 0, -1}, {1, 0, 0});
    EXPECT_EQ(flipped.normal(), glm::dvec3(0, -1, 0));
    EXPECT_DOUBLE_EQ(t.longest_edge(), std::sqrt(2.0));
    EXPECT_EQ(t.bounds().min, glm::dvec3(0, 0, -1));
    EXPECT_EQ(t.bounds().max, glm::dvec3(1, 0, 0));
}

TEST(Triangle, DegenerateTrianglesAreRecognised) {
    EXPECT_FALSE(Triangle({0, 0, 0}, {1, 0, 0}, {0, 1, 0}).is_degenerate());
    EXPECT_TRUE(Triangle({0, 0, 0}, {0, 0, 0}, {0, 0, 0}).is_degenerate());        // a point
    EXPECT_TRUE(Triangle({0, 0, 0}, {1, 1, 1}, {1, 1, 1}).is_degenerate());        // a segment
    EXPECT_TRUE(Triangle({0, 0, 0}, {1, 1, 1}, {2, 2, 2}).is_degenerate());        // collinear
    EXPECT_TRUE(Triangle({0, 0, 0}, {1, 0, 0}, {0.5, 1e-14, 0}).is_degenerate());  // too thin
    EXPECT_FALSE(Triangle({0, 0, 0}, {1, 0, 0}, {0.5, 1e-9, 0}).is_degenerate());  // thin but real
    EXPECT_FALSE(Triangle({1e4, 0, 0}, {1e4 + 1e-3, 0, 0}, {1e4, 1e-3, 0}).is_degenerate());
}

// is_degenerate skips its roots for triangles far from the tolerance: on triangles near it,
// at any scale, its verdict must be the one of the test with the roots.
TEST(Triangle, DegenerateVerdictIsTheOneOfTheTestWithRoots) {
    const auto by_roots = [](const Triangle& t, double tolerance) {
        const auto& v = t.vertices;
        const double longest = std::max(
            {glm::distance(v[0], v[1]), glm::distance(v[1], v[2]), glm::distance(v[2], v[0])});
        if (!(longest > 0.0)) return true;
        return !(glm::length(t.area_normal()) / longest > tolerance * longest);
    };
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(-1.0, 1.0), ratio(0.2, 3.0);
    int degenerate = 0, kept = 0;
    for (int i = 0; i < 200'000; ++i) {
        const double tolerance = std::array{1e-12, 1e-3, 0.1, 0.4}[i % 4];
        // Both sides of each end of the range where the roots are skipped (edges of 1e+-50).
        const double scale =
            std::array{1e-60, 0.9e-50, 1.1e-50, 1e-3, 1.0, 1e4, 0.9e50, 1.1e50, 1e60}[i / 4 % 9];
        const glm::dvec3 a(u(rng), u(rng), u(rng)), b(u(rng), u(rng), u(rng));
        const glm::dvec3 side = glm::normalize(glm::cross(b - a, glm::dvec3(u(rng), u(rng), 1.0)));
        // The apex at about `ratio` times the height the tolerance asks for.
        const double height = ratio(rng) * tolerance * glm::distance(a, b);
        const glm::dvec3 apex = glm::mix(a, b, 0.5 + 0.5 * u(rng)) + height * side;
        const Triangle t(scale * a, scale * b, scale * apex);
        const bool verdict = t.is_degenerate(tolerance);
        ASSERT_EQ(verdict, by_roots(t, tolerance)) << i << ": tolerance " << tolerance;
        (verdict ? degenerate : kept) += 1;
    }
    EXPECT_GT(degenerate, 10'000);
    EXPECT_GT(kept, 10'000);
    // A tolerance whose square underflows: the skip must not take the height for enough.
    const Triangle needle({0, 0, 0}, {0.9e50, 0, 0}, {0, 1e-150, 0});
    EXPECT_EQ(needle.is_degenerate(1e-170), by_roots(needle, 1e-170));
    EXPECT_TRUE(needle.is_degenerate(1e-170));
}

}  // namespace
}  // namespace trackphys
