#include "trackphys/geometry/triangle.hpp"

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace trackphys
