// The race's rules one at a time, on small fields over seconds: what each car decides from
// the cars around it, checked on the rule itself rather than on a whole race's outcome, so
// that no test here depends on the last bits of the physics.
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "support/error_message.hpp"
#include "tool_world_settings.hpp"
#include "trackphys/world/race_drivers.hpp"
#include "trackphys/world/world.hpp"
#include "world/track_world.hpp"
#include "world/world_scenes.hpp"

namespace trackphys {
namespace {

// A car as the rules see it: across (m left of the centreline) and along (m from the start
// line) at its autopilot's nearest centreline sample, how far past that sample it is (m),
// its position, velocity and speed, and the curvature of the road there (1/m).
struct Seen {
    double across;
    double along;
    double past_sample;
    glm::dvec3 position;
    glm::dvec3 velocity;
    double speed;
    double curvature;
};

std::vector<Seen> seen(const Track& track, const World& world, const RaceDrivers& drivers) {
    std::vector<Seen> all;
    for (std::size_t i = 0; i < drivers.car_count(); ++i) {
        const CenterlineSample& s = track.centerline[drivers.autopilot(i).nearest_sample()];
        const RigidBodyState& state = world.car(i).state();
        const glm::dvec3 offset = state.position - s.position;
        all.push_back({glm::dot(offset, s.left), s.distance, glm::dot(offset, s.tangent),
                       state.position, state.linear_velocity, world.car(i).speed(), s.curvature});
    }
    return all;
}

// How far `to` is ahead of `from` along the track (m), wrapped into [-length/2, length/2).
double wrapped(const Track& track, double from, double to) {
    double gap = std::fmod(to - from + 0.5 * track.length_m, track.length_m);
    if (gap < 0.0) gap += track.length_m;
    return gap - 0.5 * track.length_m;
}

// The first update's inputs already see the grid: car 2 stands a row behind the pole car in
// the same column, so it starts with the speed limit of following it.
TEST(RaceRules, TheFirstInputsSeeEveryCarWhereItStands) {
    const test::TrackWorld& track = test::default_track();
    World world(track.statics, cli::tool_world_settings(), track.trees);
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

// A race drives the field add_cars made: after a car is removed its pilots would drive
// the wrong cars, so drive and after_update refuse the world.
TEST(RaceRules, AWorldWhoseFieldChangedIsRefused) {
    const test::TrackWorld& track = test::default_track();
    World world(track.statics, cli::tool_world_settings(), track.trees);
    RaceDrivers drivers(track.track, CarSpec::default_car(), 3);
    drivers.add_cars(world);
    world.remove_car(1);
    for (const std::string& why : {test::error_of([&] { drivers.drive(world); }),
                                   test::error_of([&] { drivers.after_update(world); })})
        EXPECT_NE(why.find("the world has 2 cars, the race 3"), std::string::npos) << why;
}

// A car past the field is a trackphys::Error naming the accessor, the car and the count, as
// World's and PhysicsRunner's are (not the standard library's out_of_range).
TEST(RaceRules, ACarPastTheFieldIsAnErrorNamingItAndTheCount) {
    const test::TrackWorld& track = test::default_track();
    const RaceDrivers drivers(track.track, CarSpec::default_car(), 3);
    const std::string expected = ": no car 3: the race has 3 cars";
    const std::pair<const char*, std::string> calls[] = {
        {"laps", test::error_of([&] { drivers.laps(3); })},
        {"lap_times", test::error_of([&] { drivers.lap_times(3); })},
        {"target_speed", test::error_of([&] { drivers.target_speed(3); })},
        {"grip_use", test::error_of([&] { drivers.grip_use(3); })},
        {"rescues", test::error_of([&] { drivers.rescues(3); })},
        {"autopilot", test::error_of([&] { drivers.autopilot(3); })},
    };
    for (const auto& [name, why] : calls)
        EXPECT_EQ(why, std::string("RaceDrivers::") + name + expected);
    EXPECT_NO_THROW(drivers.laps(2));
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

// The field is kept in track order, which needs every centreline place along the track in
// [0, length): a track built by hand with one outside (or not a number) is refused.
TEST(RaceRules, ATrackWithPlacesOutsideItsLengthIsRefused) {
    const test::TrackWorld& track = test::default_track();
    const auto error_with = [&](double distance) {
        Track broken = track.track;
        broken.centerline[1].distance = distance;
        return test::error_of([&] { RaceDrivers(broken, CarSpec::default_car(), 2); });
    };
    EXPECT_EQ(error_with(track.track.centerline[1].distance), "(no error)");
    for (const double distance : {-1.0, track.track.length_m, std::nan("")})
        EXPECT_NE(error_with(distance).find("RaceDrivers: a centreline sample at"),
                  std::string::npos)
            << distance;
    Track no_length = track.track;
    no_length.length_m = std::numeric_limits<double>::infinity();
    EXPECT_EQ(test::error_of([&] { RaceDrivers(no_length, CarSpec::default_car(), 2); }),
              "RaceDrivers: the track's length must be finite and > 20 m (a lane change looks "
              "that far back), got inf m");
    // Shorter than a lane change looks back, a car would look more than a lap behind.
    Track short_loop;
    short_loop.length_m = 15.0;
    short_loop.centerline.resize(3);
    short_loop.centerline[1].distance = 5.0;
    short_loop.centerline[2].distance = 10.0;
    EXPECT_NE(test::error_of([&] {
                  RaceDrivers(short_loop, CarSpec::default_car(), 1);
              }).find("must be finite and > 20 m"),
              std::string::npos);
}

// A progress whose third car is off the centreline is refused before any car's is set.
TEST(RaceRules, ARefusedProgressChangesNoCar) {
    const test::TrackWorld& track = test::default_track();
    RaceDrivers drivers(track.track, CarSpec::default_car(), 3);
    RaceProgress progress = drivers.progress();
    for (AutopilotProgress& pilot : progress.pilots) pilot = {7, 2, true};
    progress.pilots[2].nearest_sample = track.track.centerline.size();
    EXPECT_NE(
        test::error_of([&] { drivers.set_progress(progress); }).find("is beyond the centreline's"),
        std::string::npos);
    for (std::size_t i = 0; i < drivers.car_count(); ++i) {
        EXPECT_EQ(drivers.autopilot(i).laps(), 0) << "car " << i;
        EXPECT_FALSE(drivers.autopilot(i).progress().located) << "car " << i;
    }
}

// The drivers keep their own copy of what they read of the track: a field whose track was
// overwritten after the drivers were made (a temporary, a reused variable) races as one
// whose track stayed.
TEST(RaceRules, TheDriversOutliveTheirTrack) {
    const test::TrackWorld& track = test::default_track();
    const auto race = [&](bool overwrite_the_track) {
        Track given = track.track;
        RaceDrivers drivers(given, CarSpec::default_car(), 2);
        if (overwrite_the_track) {
            given.centerline.assign(3, given.centerline[5]);
            given.length_m = 50.0;
        }
        World world(track.statics, cli::tool_world_settings(), track.trees);
        drivers.add_cars(world);
        for (int update = 0; update < 50; ++update) {
            drivers.drive(world);
            world.update();
            drivers.after_update(world);
        }
        return world.state_hash();
    };
    EXPECT_EQ(race(true), race(false));
}

// The field's autopilots share one copy of the track's centreline (a copy each would be
// most of a race's memory beside the road).
TEST(RaceRules, TheFieldSharesOneCenterline) {
    const test::TrackWorld& track = test::default_track();
    const RaceDrivers drivers(track.track, CarSpec::default_car(), 3);
    const std::vector<CenterlineSample>& first = drivers.autopilot(0).centerline();
    EXPECT_NE(&first, &track.track.centerline);
    EXPECT_EQ(first.size(), track.track.centerline.size());
    for (std::size_t i = 1; i < drivers.car_count(); ++i)
        EXPECT_EQ(&drivers.autopilot(i).centerline(), &first) << "car " << i;
}

// Three cars, passing ruled out (merge_gap and pass_look_ahead as long as the track): the
// fastest car, a row behind the slowest in the same lane, catches it in the first turns and
// then follows it at its gap (follow_distance + follow_time v) and its speed. The speed rule
// is proportional (1 m/s per metre off the gap), so the follower rides a little inside the
// gap while both brake and a little outside it while both accelerate (hence the tolerance
// below). Without the rule, it would run into the car ahead.
TEST(RaceRules, AFollowerThatCannotPassKeepsItsGapAndMatchesSpeed) {
    const test::TrackWorld& track = test::default_track();
    World world(track.statics, cli::tool_world_settings(), track.trees);
    RaceSettings settings;
    settings.merge_gap = settings.pass_look_ahead = track.track.length_m;
    RaceDrivers drivers(track.track, CarSpec::default_car(), 3, settings);
    drivers.add_cars(world);
    constexpr double kCaughtUp = 5.0;  // s
    double inside = 0.0, outside = 0.0, speed_difference = 0.0;
    int updates = 0;
    while (world.time() < 30.0) {
        drivers.drive(world);
        world.update();
        drivers.after_update(world);
        ASSERT_EQ(drivers.progress().lanes[2], settings.lane_offset) << "car 2 pulled out";
        const std::vector<Seen> cars = seen(track.track, world, drivers);
        const double gap = wrapped(track.track, cars[2].along + cars[2].past_sample,
                                   cars[0].along + cars[0].past_sample);
        const double keep = settings.follow_distance + settings.follow_time * cars[2].speed;
        inside = std::max(inside, keep - gap);
        if (world.time() < kCaughtUp) continue;
        outside = std::max(outside, gap - keep);
        speed_difference += std::abs(cars[2].speed - cars[0].speed);
        ++updates;
    }
    EXPECT_LT(inside, 1.5) << "m inside the following gap";
    EXPECT_LT(outside, 4.0) << "m behind the following gap once caught up";
    EXPECT_LT(speed_difference / updates, 1.5) << "m/s from the speed of the car ahead, mean";
}

// Four cars racing 90 s by the default rules: every lane change (out to pass, or back)
// begins where the turn asks at most swerve_turn_accel of the tyres, and into a lane with
// nobody in it from 20 m behind to merge_gap ahead and the car ahead there not closing in.
// The cars spend most of the time in turns faster than that, so a change begun anywhere
// would break the first rule.
TEST(RaceRules, LaneChangesBeginOnlyIntoAFreeGapAndNotInAFastTurn) {
    const test::TrackWorld& track = test::default_track();
    World world(track.statics, cli::tool_world_settings(), track.trees);
    const RaceSettings settings;
    constexpr double kMirror = -20.0;  // m
    const std::size_t n = 4;
    RaceDrivers drivers(track.track, CarSpec::default_car(), n, settings);
    drivers.add_cars(world);
    int changes = 0;
    while (world.time() < 90.0) {
        const std::vector<double> lanes = drivers.progress().lanes;
        const std::vector<Seen> cars = seen(track.track, world, drivers);
        drivers.drive(world);
        for (std::size_t i = 0; i < n; ++i) {
            const double lane = drivers.progress().lanes[i];
            if (lane == lanes[i]) continue;
            ++changes;
            SCOPED_TRACE(testing::Message()
                         << "car " << i << " to lane " << lane << " at " << world.time() << " s");
            EXPECT_LE(cars[i].speed * cars[i].speed * std::abs(cars[i].curvature),
                      settings.swerve_turn_accel);
            // The nearest car in the new lane from the mirror on, as far as lanes are read.
            double nearest = std::numeric_limits<double>::infinity();
            std::size_t ahead = i;
            for (std::size_t j = 0; j < n; ++j) {
                if (j == i || std::abs(cars[j].across - lane) > settings.lane_width) continue;
                double gap = wrapped(track.track, cars[i].along, cars[j].along);
                if (gap < kMirror) gap += track.track.length_m;
                if (gap <= settings.pass_look_ahead && gap < nearest) nearest = gap, ahead = j;
            }
            EXPECT_GE(nearest, settings.merge_gap) << "car " << ahead << " in the gap";
            if (ahead == i) continue;
            const glm::dvec3 toward = cars[ahead].position - cars[i].position;
            EXPECT_LE(glm::dot(cars[i].velocity - cars[ahead].velocity, toward), 0.0)
                << "closing in on car " << ahead;
        }
        world.update();
        drivers.after_update(world);
    }
    EXPECT_GE(changes, 4) << "lane changes: nobody passed";
}

}  // namespace
}  // namespace trackphys
