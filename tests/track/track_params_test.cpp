#include "trackphys/track/track_params.hpp"

#include <functional>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "trackphys/error.hpp"
#include "trackphys/track/track.hpp"

namespace trackphys {
namespace {

// The error message for params, or "" when they are valid.
std::string problem(const TrackParams& params) {
    try {
        validate_track_params(params);
    } catch (const Error& e) {
        return e.what();
    }
    return {};
}

TEST(TrackParams, DefaultsAreValid) { EXPECT_EQ(problem(TrackParams{}), ""); }

TEST(TrackParams, EachBadFieldIsNamed) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double inf = std::numeric_limits<double>::infinity();
    struct Case {
        const char* field;
        std::function<void(TrackParams&)> spoil;
    };
    const std::vector<Case> cases = {
        {"length_m", [](TrackParams& p) { p.length_m = 10.0; }},
        {"length_m", [=](TrackParams& p) { p.length_m = nan; }},
        {"length_m", [](TrackParams& p) { p.length_m = 220.0; }},  // too short for 25 m turns
        {"elevation_amplitude_m", [](TrackParams& p) { p.elevation_amplitude_m = 51.0; }},
        {"width_m", [](TrackParams& p) { p.width_m = 0.0; }},
        {"width_m", [=](TrackParams& p) { p.width_m = inf; }},
        {"max_bank_deg", [](TrackParams& p) { p.max_bank_deg = -1.0; }},
        {"max_bank_deg", [](TrackParams& p) { p.max_bank_deg = 80.0; }},
        {"full_bank_radius_m", [](TrackParams& p) { p.full_bank_radius_m = 0.0; }},
        {"elevation_amplitude_m", [](TrackParams& p) { p.elevation_amplitude_m = -2.0; }},
        {"wall_height_m", [](TrackParams& p) { p.wall_height_m = 0.0; }},
        {"wall_thickness_m", [=](TrackParams& p) { p.wall_thickness_m = nan; }},
        {"min_turn_radius_m",
         [](TrackParams& p) { p.min_turn_radius_m = 8.0; }},  // inner edge folds
        {"edge_tight_m", [](TrackParams& p) { p.edge_tight_m = 0.0; }},
        {"edge_tight_m",
         [](TrackParams& p) {
             p.edge_tight_m = 0.05;
             p.strips = 200;
         }},                                                                   // budget
        {"edge_straight_m", [](TrackParams& p) { p.edge_straight_m = 0.2; }},  // < edge_tight_m
        {"tight_radius_m", [](TrackParams& p) { p.tight_radius_m = -5.0; }},
        {"strips", [](TrackParams& p) { p.strips = 0; }},
        {"strips", [](TrackParams& p) { p.strips = 1000; }},
        {"chunk_length_m", [](TrackParams& p) { p.chunk_length_m = 1.0; }},
    };
    for (const Case& c : cases) {
        TrackParams params;
        c.spoil(params);
        const std::string message = problem(params);
        EXPECT_NE(message.find(std::string("TrackParams.") + c.field), std::string::npos)
            << "expected an error naming " << c.field << ", got: '" << message << "'";
    }
}

TEST(TrackParams, GenerateTrackRejectsBadParams) {
    TrackParams params;
    params.width_m = -3.0;
    EXPECT_THROW(generate_track(params), Error);
}

}  // namespace
}  // namespace trackphys
