#include "track/bezier_loop.hpp"

#include <cmath>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

namespace trackphys::track_detail {
namespace {

std::vector<glm::dvec3> wobbly_points() {
    // An uneven, hilly loop: different spacings and heights on every segment.
    return {{0, 0, 0}, {120, 4, -10}, {260, -3, 40}, {300, 8, 180}, {150, 0, 260}, {40, -6, 150}};
}

TEST(BezierLoop, IsC1AtEveryJoint) {
    const BezierLoop loop(wobbly_points());
    const std::size_t n = loop.segment_count();
    for (std::size_t i = 0; i < n; ++i) {
        const std::size_t next = (i + 1) % n;
        // Position and first derivative agree where segment i ends and segment i+1 starts.
        EXPECT_NEAR(glm::distance(loop.segment_position(i, 1.0), loop.segment_position(next, 0.0)),
                    0.0, 1e-12);
        const glm::dvec3 end = loop.segment_derivative(i, 1.0);
        const glm::dvec3 start = loop.segment_derivative(next, 0.0);
        EXPECT_LE(glm::distance(end, start), 1e-12 * glm::length(start)) << "joint " << next;
        // And the curve passes through its control points.
        EXPECT_EQ(loop.segment_position(next, 0.0), loop.points()[next]);
    }
}

TEST(BezierLoop, ClosesExactlyAtItsLength) {
    const BezierLoop loop(wobbly_points());
    EXPECT_EQ(loop.at(0.0).position, loop.points()[0]);
    EXPECT_EQ(loop.at(loop.length()).position, loop.points()[0]);
    EXPECT_LE(glm::distance(loop.at(loop.length() - 1e-9).position, loop.points()[0]), 1e-8);
    EXPECT_LE(glm::distance(loop.at(0.0).tangent, loop.at(loop.length() - 1e-12).tangent), 1e-9);
}

TEST(BezierLoop, ArcLengthParametrisationIsAccurate) {
    const BezierLoop loop(wobbly_points());
    // Consecutive points 1 cm apart in arc length are 1 cm apart in space: the chord of a
    // 1 cm arc is shorter by only kappa^2 d^3 / 24 (< 1e-12 m for these radii).
    const double step = 0.01;
    double chord_sum = 0.0;
    glm::dvec3 previous = loop.at(0.0).position;
    const auto steps = static_cast<int>(std::floor(loop.length() / step));
    for (int k = 1; k <= steps; ++k) {
        const glm::dvec3 p = loop.at(k * step).position;
        const double chord = glm::distance(previous, p);
        ASSERT_NEAR(chord, step, 1e-9) << "at " << k * step << " m";
        chord_sum += chord;
        previous = p;
    }
    chord_sum += glm::distance(previous, loop.at(loop.length()).position);
    EXPECT_NEAR(chord_sum, loop.length(), 1e-6);
}

TEST(BezierLoop, TangentIsUnitAndCurvatureMatchesACircle) {
    // Catmull-Rom through 64 points of a circle of radius 100 stays within a fraction of a
    // percent of it. The sign convention: curvature > 0 turns towards left = +Y x tangent.
    std::vector<glm::dvec3> points;
    const double radius = 100.0;
    for (int i = 0; i < 64; ++i) {
        const double a = 2.0 * std::numbers::pi * i / 64;
        points.emplace_back(radius * std::cos(a), 0.0, radius * std::sin(a));
    }
    const BezierLoop loop(points);
    EXPECT_NEAR(loop.length(), 2.0 * std::numbers::pi * radius, 0.01);
    for (double s = 0.0; s < loop.length(); s += 7.3) {
        const BezierLoop::Point p = loop.at(s);
        EXPECT_NEAR(glm::length(p.tangent), 1.0, 1e-12);
        const glm::dvec3 left(p.tangent.z, 0.0, -p.tangent.x);
        // The centre (origin) is on the left or the right; the curvature's sign says which.
        const double towards_centre = glm::dot(-p.position, left);
        EXPECT_NEAR(std::abs(p.horizontal_curvature), 1.0 / radius, 1e-4);
        EXPECT_GT(p.horizontal_curvature * towards_centre, 0.0);
    }
}

}  // namespace
}  // namespace trackphys::track_detail
