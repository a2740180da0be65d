#include "trackphys/collision/swept_ellipsoid.hpp"

#include <algorithm>
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

namespace trackphys {
namespace {

const glm::dvec3 kWheel(0.15, 0.35, 0.35);

// Whether p lies in the swept shape, by its definition: within the scaled ellipsoid about
// some center on the segment. The scaled level ||D^-1 A^T (p - c(t))|| / scale is convex in
// t, so a golden-section search finds its minimum.
bool inside(const SweptEllipsoid& shape, const glm::dvec3& p) {
    const Ellipsoid& e = shape.ellipsoid;
    auto level = [&](double t) {
        const glm::dvec3 c = e.center() + t * (shape.end - e.center());
        const glm::dvec3 local = (p - c) * e.sorted_axes() / e.sorted_radii();
        return glm::length(local) / shape.scale();
    };
    double lo = 0.0, hi = 1.0;
    const double golden = 0.5 * (std::sqrt(5.0) - 1.0);
    for (int k = 0; k < 80; ++k) {
        const double a = hi - golden * (hi - lo), b = lo + golden * (hi - lo);
        if (level(a) < level(b))
            hi = b;
        else
            lo = a;
    }
    return std::min({level(0.0), level(1.0), level(0.5 * (lo + hi))}) <= 1.0 + 1e-12;
}

// A point of the inner shape: the scaled ellipsoid's surface point in direction s, about
// the center at t along its segment.
glm::dvec3 surface_point(const SweptEllipsoid& shape, const glm::dvec3& s, double t) {
    const Ellipsoid& e = shape.ellipsoid;
    const glm::dvec3 c = e.center() + t * (shape.end - e.center());
    return c + e.sorted_axes() * (e.sorted_radii() * shape.scale() * glm::normalize(s));
}

// Whenever contains() says yes, every sampled point of the inner shape is inside the outer
// one; and small enough moves, turns and margins do say yes often.
TEST(SweptEllipsoid, ContainsIsSoundForRandomMovesAndTurns) {
    std::mt19937_64 rng(5);
    std::normal_distribution<double> gauss;
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    int contained = 0, refused = 0;
    for (int i = 0; i < 3000; ++i) {
        const glm::dquat q0 =
            glm::normalize(glm::dquat(gauss(rng), gauss(rng), gauss(rng), gauss(rng)));
        const glm::dvec3 c0(100.0 * gauss(rng), 10.0 * gauss(rng), 100.0 * gauss(rng));
        const glm::dvec3 v(30.0 * gauss(rng), 3.0 * gauss(rng), 30.0 * gauss(rng));
        const SweptEllipsoid outer{Ellipsoid(c0, q0, kWheel), c0 + 0.003 * v,
                                   0.01 + 0.01 * unit(rng)};
        // A later step: moved along the path with a small deviation, turned a little.
        const double along = unit(rng);
        const glm::dvec3 deviation =
            0.004 * unit(rng) * glm::normalize(glm::dvec3(gauss(rng), gauss(rng), gauss(rng)));
        const glm::dvec3 axis = glm::normalize(glm::dvec3(gauss(rng), gauss(rng), gauss(rng)));
        const glm::dquat q1 = glm::angleAxis(0.01 * unit(rng), axis) * q0;
        const glm::dvec3 c1 = c0 + along * 0.003 * v + deviation;
        const SweptEllipsoid inner{Ellipsoid(c1, q1, kWheel), c1 + 0.001 * v, 0.01};
        if (!outer.contains(inner)) {
            ++refused;
            continue;
        }
        ++contained;
        for (int k = 0; k < 40; ++k) {
            const glm::dvec3 p =
                surface_point(inner, {gauss(rng), gauss(rng), gauss(rng)}, unit(rng));
            ASSERT_TRUE(inside(outer, p)) << "case " << i << " sample " << k;
        }
    }
    EXPECT_GT(contained, 300);
    EXPECT_GT(refused, 300);
}

TEST(SweptEllipsoid, RefusesOtherRadiiAMoveBeyondTheMarginAndALargerMargin) {
    const glm::dquat q(1, 0, 0, 0);
    const SweptEllipsoid outer{Ellipsoid({0, 0, 0}, q, kWheel), {1, 0, 0}, 0.02};
    EXPECT_TRUE(outer.contains({Ellipsoid({0.5, 0, 0}, q, kWheel), {0.9, 0, 0}, 0.01}));
    EXPECT_FALSE(
        outer.contains({Ellipsoid({0.5, 0, 0}, q, {0.15, 0.35, 0.36}), {0.9, 0, 0}, 0.01}));
    EXPECT_FALSE(outer.contains({Ellipsoid({0.5, 0.011, 0}, q, kWheel), {0.9, 0, 0}, 0.01}));
    EXPECT_FALSE(outer.contains({Ellipsoid({0.5, 0, 0}, q, kWheel), {1.02, 0, 0}, 0.01}));
    EXPECT_FALSE(outer.contains({Ellipsoid({0.5, 0, 0}, q, kWheel), {0.9, 0, 0}, 0.021}));
    // Turned by 0.1 rad: points 0.35 m out move by ~3.5 cm, more than the 1 cm to spare.
    EXPECT_FALSE(
        outer.contains({Ellipsoid({0.5, 0, 0}, glm::angleAxis(0.1, glm::dvec3(1, 0, 0)), kWheel),
                        {0.9, 0, 0},
                        0.01}));
}

TEST(SweptEllipsoid, BoundsHoldTheScaledEllipsoidAlongTheSegment) {
    std::mt19937_64 rng(8);
    std::normal_distribution<double> gauss;
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    for (int i = 0; i < 200; ++i) {
        const glm::dquat q =
            glm::normalize(glm::dquat(gauss(rng), gauss(rng), gauss(rng), gauss(rng)));
        const SweptEllipsoid shape{Ellipsoid({gauss(rng), gauss(rng), gauss(rng)}, q, kWheel),
                                   {gauss(rng), gauss(rng), gauss(rng)},
                                   0.05 * unit(rng)};
        const Aabb box = shape.bounds();
        for (int k = 0; k < 50; ++k) {
            const glm::dvec3 p =
                surface_point(shape, {gauss(rng), gauss(rng), gauss(rng)}, unit(rng));
            ASSERT_TRUE(box.padded(1e-12).contains(p)) << "case " << i;
        }
    }
}

}  // namespace
}  // namespace trackphys
