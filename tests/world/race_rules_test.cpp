// The race's rules one at a time, on small fields over seconds: what each car decides from
// the cars around it, checked on the rule itself rather than on a whole race's outcome, so
// that no test here depends on the last bits of the physics.
#include <cmath>
#include <limits>

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace trackphys
