#include "track/track_shape.hpp"

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "trackphys/error.hpp"

namespace trackphys::track_detail {
namespace {

std::vector<glm::dvec3> circle(double radius, int count) {
    std::vector<glm::dvec3> points;
    for (int i = 0; i < count; ++i) {
        const double a = 2.0 * std::numbers::pi * i / count;
        points.emplace_back(radius * std::cos(a), 0.0, radius * std::sin(a));
    }
    return points;
}

TEST(TrackShape, AcceptsACircle) {
    TrackParams params;
    EXPECT_EQ(shape_problem(BezierLoop(circle(800.0, 16)), params), "");
}

TEST(TrackShape, RejectsAFigureEight) {
    // A lemniscate crosses itself at the origin.
    std::vector<glm::dvec3> points;
    for (int i = 0; i < 32; ++i) {
        const double a = 2.0 * std::numbers::pi * i / 32;
        points.emplace_back(1000.0 * std::sin(a), 0.0, 500.0 * std::sin(a) * std::cos(a));
    }
    const std::string why = shape_problem(BezierLoop(points), TrackParams{});
    EXPECT_NE(why.find("comes within"), std::string::npos) << why;
}

TEST(TrackShape, RejectsTwoRoadsTooCloseWithoutCrossing) {
    // A dumbbell: two wide bulbs joined by a waist where the two sides of the loop run
    // 18 m apart (centre to centre), closer than two 14 m roads with walls allow, though
    // the curve never crosses itself and no turn is tight.
    std::vector<glm::dvec3> points;
    for (int i = 0; i < 128; ++i) {
        const double a = 2.0 * std::numbers::pi * i / 128;
        const double c = std::cos(a);
        points.emplace_back(600.0 * c, 0.0, 300.0 * std::sin(a) * (0.03 + 0.97 * c * c));
    }
    const std::string why = shape_problem(BezierLoop(points), TrackParams{});
    EXPECT_NE(why.find("comes within"), std::string::npos) << why;
}

TEST(TrackShape, RejectsATurnTighterThanTheMinimumRadius) {
    TrackParams params;
    params.min_turn_radius_m = 150.0;
    const std::string why = shape_problem(BezierLoop(circle(100.0, 16)), params);
    EXPECT_NE(why.find("min_turn_radius_m"), std::string::npos) << why;
}

TEST(TrackShape, ScalesToTheRequestedLength) {
    TrackParams params;
    params.elevation_amplitude_m = 20.0;
    std::mt19937_64 rng(3);
    const BezierLoop loop = scale_to_length(draw_control_points(params, 1.0, rng), 3210.0);
    EXPECT_NEAR(loop.length(), 3210.0, 3210.0 * 1e-9);
}

TEST(TrackShape, EveryAttemptRelaxesTowardsACircleThatPasses) {
    // Even the most demanding valid parameters get a shape: at worst the circle.
    TrackParams params;
    params.length_m = 3.0 * std::numbers::pi * params.min_turn_radius_m * 1.01;
    params.seed = 5;
    const TrackShape shape = make_track_shape(params);
    EXPECT_EQ(shape_problem(shape.loop, params), "");
    EXPECT_LT(shape.rejected, kMaxShapeAttempts);
}

}  // namespace
}  // namespace trackphys::track_detail
