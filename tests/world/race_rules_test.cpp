// The race's rules one at a time, on small fields over seconds: what each car decides from
// the cars around it, checked on the rule itself rather than on a whole race's outcome, so
// that no test here depends on the last bits of the physics.
#include <cmath>
#include <limits>
#include <string>

#include <gtest/gtest.h>

#include "support/error_message.hpp"
#include "trackphys/world/race_drivers.hpp"
#include "trackphys/world/world.hpp"
#include "world/track_world.hpp"

namespace trackphys {
namespace {

// The first update's inputs already see the grid: car 2 stands a row behind the pole car in
// the same column, so it starts with the speed limit of following it.
TEST(RaceRules, TheFirstInputsSeeEveryCarWhereItStands) {
    const test::TrackWorld& track = test::default_track();
    World world(track.statics, WorldSettings{}, track.trees);
    RaceSettings settings;
    settings.grid.row_gap = 20.0;
    RaceDrivers drivers(track.track, CarSpec::default_car(), 3, settings);
    drivers.add_cars(world);
    drivers.drive(world);
    // At rest, a row behind: 1 m/s per metre beyond the following distance.
    const double expected = settings.grid.row_gap - settings.follow_distance;
    EXPECT_NEAR(drivers.autopilot(2).speed_limit(), expected, 0.5);
    EXPECT_EQ(drivers.autopilot(0).speed_limit(), std::numeric_limits<double>::infinity());
}

// The lanes are read no farther than pass_look_ahead, so a merge_gap beyond it would act as
// pass_look_ahead: refused, naming both. The rule thresholds are validated with the rest.
TEST(RaceRules, SettingsThatCannotActAsWrittenAreRefused) {
    const test::TrackWorld& track = test::default_track();
    const auto error_with = [&](auto change) {
        RaceSettings settings;
        change(settings);
        return test::error_of(
            [&] { RaceDrivers(track.track, CarSpec::default_car(), 2, settings); });
    };
    EXPECT_EQ(error_with([](RaceSettings& s) { s.merge_gap = 61.0; }),
              "RaceSettings: merge_gap (61 m) must be <= pass_look_ahead (60 m), as far as the "
              "lanes are read");
    EXPECT_EQ(error_with([](RaceSettings& s) { s.merge_gap = s.pass_look_ahead = 1e9; }),
              "(no error)");
    for (const auto& change : {+[](RaceSettings& s) { s.pass_closing = -1.0; },
                               +[](RaceSettings& s) { s.swerve_turn_accel = -1.0; },
                               +[](RaceSettings& s) { s.swerve_turn_accel = std::nan(""); }})
        EXPECT_NE(error_with(change).find("pass_closing and swerve_turn_accel must be >= 0"),
                  std::string::npos);
    EXPECT_EQ(error_with([](RaceSettings& s) {
                  s.swerve_turn_accel = std::numeric_limits<double>::infinity();
              }),
              "(no error)");
}

}  // namespace
}  // namespace trackphys
