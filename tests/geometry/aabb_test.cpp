#include "trackphys/geometry/aabb.hpp"

#include <gtest/gtest.h>

namespace trackphys {
namespace {

TEST(Aabb, DefaultIsEmptyAndGrowsFromNothing) {
    Aabb box;
    EXPECT_TRUE(box.empty());
    EXPECT_EQ(box.surface_area(), 0.0);
    box.expand(glm::dvec3(1, 2, 3));
    EXPECT_FALSE(box.empty());
    EXPECT_EQ(box.min, glm::dvec3(1, 2, 3));
    EXPECT_EQ(box.max, glm::dvec3(1, 2, 3));
    box.expand(Aabb{});  // an empty box changes nothing
    EXPECT_EQ(box.max, glm::dvec3(1, 2, 3));
    box.expand(glm::dvec3(-1, 4, 3));
    EXPECT_EQ(box.min, glm::dvec3(-1, 2, 3));
    EXPECT_EQ(box.max, glm::dvec3(1, 4, 3));
}

TEST(Aabb, OverlapIsClosedAndEmptyBoxesOverlapNothing) {
    const Aabb a{{0, 0, 0}, {1, 1, 1}};
    EXPECT_TRUE(a.overlaps(Aabb{{1, 1, 1}, {2, 2, 2}}));  // touching corners
    EXPECT_FALSE(a.overlaps(Aabb{{1.0000001, 0, 0}, {2, 1, 1}}));
    EXPECT_FALSE(a.overlaps(Aabb{}));
    EXPECT_FALSE(Aabb{}.overlaps(a));
    EXPECT_TRUE(a.contains({0.5, 1.0, 0.0}));
    EXPECT_FALSE(a.contains({0.5, 1.5, 0.0}));
}

TEST(Aabb, PaddingCenterAndArea) {
    const Aabb a{{0, 0, 0}, {1, 2, 3}};
    EXPECT_EQ(a.center(), glm::dvec3(0.5, 1.0, 1.5));
    EXPECT_DOUBLE_EQ(a.surface_area(), 2.0 * (2.0 + 6.0 + 3.0));
    const Aabb p = a.padded(0.5);
    EXPECT_EQ(p.min, glm::dvec3(-0.5));
    EXPECT_EQ(p.max, glm::dvec3(1.5, 2.5, 3.5));
}

}  // namespace
}  // namespace trackphys
