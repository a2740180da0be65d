#include "trackphys/geometry/ellipsoid.hpp"

#include <cmath>
#include <limits>
#include <random>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

#include "trackphys/error.hpp"

namespace trackphys {
namespace {

const glm::dquat identity(1.0, 0.0, 0.0, 0.0);

TEST(Ellipsoid, SortsAxesDescendingAndKeepsAProperRotation) {
    std::mt19937_64 rng(99);
    std::uniform_real_distribution<double> radius(0.05, 3.0);
    std::normal_distribution<double> normal;
    for (int i = 0; i < 1000; ++i) {
        const glm::dvec3 axes(radius(rng), radius(rng), radius(rng));
        const glm::dquat q =
            glm::normalize(glm::dquat(normal(rng), normal(rng), normal(rng), normal(rng)));
        const Ellipsoid e({1, 2, 3}, q, axes);
        const glm::dvec3 r = e.sorted_radii();
        ASSERT_GE(r.x, r.y);
        ASSERT_GE(r.y, r.z);
        const glm::dmat3& m = e.sorted_axes();
        ASSERT_NEAR(glm::determinant(m), 1.0, 1e-12);
        // Each sorted axis is the given local axis of that radius, in world space.
        const glm::dmat3 rotation = glm::mat3_cast(q);
        for (int k = 0; k < 3; ++k) {
            int given = 0;
            while (axes[given] != r[k] ||
                   std::abs(std::abs(glm::dot(rotation[given], m[k])) - 1.0) > 1e-12) {
                ++given;
                ASSERT_LT(given, 3) << "sorted axis " << k << " matches no given axis";
            }
        }
        // A surface point of the given ellipsoid is on the sorted one too.
        const glm::dvec3 world = e.center() + rotation * glm::dvec3(0.0, axes.y, 0.0);
        const glm::dvec3 local = e.to_sorted_local(world);
        const double level = glm::dot(local / r, local / r);
        ASSERT_NEAR(level, 1.0, 1e-12);
    }
}

TEST(Ellipsoid, BoundsAreTight) {
    const Ellipsoid e({1, 0, 0}, glm::angleAxis(glm::radians(90.0), glm::dvec3(0, 0, 1)),
                      {2.0, 0.5, 0.25});
    // Rotating 90 degrees about z turns the 2 m x axis into world y.
    EXPECT_NEAR(e.bounds().max.x, 1.5, 1e-12);
    EXPECT_NEAR(e.bounds().max.y, 2.0, 1e-12);
    EXPECT_NEAR(e.bounds().max.z, 0.25, 1e-12);
    EXPECT_NEAR(e.bounds().min.y, -2.0, 1e-12);
    EXPECT_EQ(e.bounding_radius(), 2.0);
}

TEST(Ellipsoid, NormalisesTheOrientation) {
    const Ellipsoid e({0, 0, 0}, glm::dquat(2.0, 0.0, 0.0, 0.0), {1, 2, 3});
    EXPECT_EQ(e.orientation(), identity);
    EXPECT_EQ(e.semi_axes(), glm::dvec3(1, 2, 3));
    EXPECT_EQ(e.sorted_radii(), glm::dvec3(3, 2, 1));
}

TEST(Ellipsoid, TransformedEqualsBuildingTheMovedEllipsoid) {
    std::mt19937_64 rng(7);
    std::normal_distribution<double> normal;
    for (int i = 0; i < 1000; ++i) {
        const glm::dquat local =
            glm::normalize(glm::dquat(normal(rng), normal(rng), normal(rng), normal(rng)));
        const glm::dquat motion =
            glm::normalize(glm::dquat(normal(rng), normal(rng), normal(rng), normal(rng)));
        const glm::dvec3 center(normal(rng), normal(rng), normal(rng));
        const glm::dvec3 translation(normal(rng) * 100.0, normal(rng), normal(rng));
        const glm::dvec3 axes(0.35, 0.15, 0.35);
        const Ellipsoid body(center, local, axes);
        const Ellipsoid moved = body.transformed(motion, translation);
        const Ellipsoid rebuilt(motion * center + translation, motion * local, axes);
        ASSERT_LE(glm::length(moved.center() - rebuilt.center()), 1e-12);
        ASSERT_EQ(moved.sorted_radii(), rebuilt.sorted_radii());
        for (int k = 0; k < 3; ++k)
            ASSERT_LE(glm::length(moved.sorted_axes()[k] - rebuilt.sorted_axes()[k]), 1e-14);
        const glm::dvec3 p(normal(rng), normal(rng), normal(rng));
        ASSERT_LE(glm::length(moved.to_sorted_local(p) - rebuilt.to_sorted_local(p)), 1e-12);
    }
}

TEST(Ellipsoid, RejectsInvalidInputWithAMessage) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double inf = std::numeric_limits<double>::infinity();
    struct Case {
        glm::dvec3 center;
        glm::dquat orientation;
        glm::dvec3 axes;
        const char* expected;
    };
    const Case cases[] = {
        {{0, 0, 0}, identity, {0, 1, 1}, "semi-axis x"},
        {{0, 0, 0}, identity, {1, -1, 1}, "semi-axis y"},
        {{0, 0, 0}, identity, {1, 1, nan}, "semi-axis z"},
        {{0, 0, 0}, identity, {1, inf, 1}, "semi-axis y"},
        {{nan, 0, 0}, identity, {1, 1, 1}, "center"},
        {{0, 0, 0}, glm::dquat(0, 0, 0, 0), {1, 1, 1}, "zero"},
        {{0, 0, 0}, glm::dquat(nan, 0, 0, 0), {1, 1, 1}, "orientation"},
    };
    for (const Case& c : cases) {
        try {
            Ellipsoid(c.center, c.orientation, c.axes);
            ADD_FAILURE() << "accepted an invalid ellipsoid: " << c.expected;
        } catch (const Error& error) {
            EXPECT_NE(std::string(error.what()).find(c.expected), std::string::npos)
                << error.what();
        }
        std::string why;
        EXPECT_FALSE(Ellipsoid::make(c.center, c.orientation, c.axes, &why).has_value());
        EXPECT_NE(why.find(c.expected), std::string::npos) << why;
    }
    EXPECT_TRUE(Ellipsoid::make({0, 0, 0}, identity, {1, 1, 1}).has_value());
}

}  // namespace
}  // namespace trackphys
