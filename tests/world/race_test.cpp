// Issue 16's race: a field of default cars racing laps of the default track finishes clean
// (every car, no reset, on the road between the walls, cars that touch but never sink into
// each other), and gives the same bits on 1, 2 and 4 threads and across a snapshot. The
// 20-car, 3-lap race takes minutes, so it is labelled "long" (tests/world/CMakeLists.txt);
// the 8-car lap checks the same in the default run.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "tool_world_settings.hpp"
#include "trackphys/world/race_drivers.hpp"
#include "trackphys/world/world.hpp"
#include "world/track_world.hpp"
#include "world/world_scenes.hpp"

namespace trackphys {
namespace {

constexpr double kSaveAt = 30.0;      // s
constexpr double kGiveUpAt = 1200.0;  // s: far longer than any of these races takes

struct RaceRun {
    std::uint64_t hash = 0;
    int fewest_laps = 0;
    std::uint64_t resets = 0;
    std::uint64_t car_contacts = 0;
    double deepest = 0.0;   // the deepest car-car penetration (m)
    double lowest_m = 1e9;  // the lowest centre of mass above the road (m)
    double widest_m = 0.0;  // the farthest a centre of mass got from the centreline (m)
    std::optional<WorldSnapshot> snapshot;
    RaceProgress progress;
};

struct Race {
    std::size_t cars;
    int laps;
    double nudge_m = 0.0;  // every car's start moved this far forward
};

// Runs `race` to its laps; saves at kSaveAt when asked, or resumes from `from`.
RaceRun run(const Race& race, int threads, bool save, const RaceRun* from = nullptr) {
    const test::TrackWorld& track = test::default_track();
    WorldSettings settings;
    settings.threads = threads;
    World world(track.statics, settings, track.trees);
    RaceDrivers drivers(track.track, CarSpec::default_car(), race.cars);
    drivers.add_cars(world);
    if (race.nudge_m != 0.0) {
        for (std::size_t i = 0; i < race.cars; ++i) {
            RigidBodyState start = world.car(i).state();
            start.position += start.orientation * glm::dvec3(0.0, 0.0, 1.0) * race.nudge_m;
            world.car(i).set_state(start);
        }
    }
    if (from) {
        world.restore_state(*from->snapshot);
        drivers.set_progress(from->progress);
    }
    RaceRun result;
    while (drivers.fewest_laps() < race.laps && world.time() < kGiveUpAt) {
        drivers.drive(world);
        world.update();
        drivers.after_update(world);
        result.car_contacts += world.last_profile().car_contacts;
        result.deepest = std::max(result.deepest, world.last_profile().max_car_penetration);
        for (std::size_t i = 0; i < race.cars; ++i) {
            const CenterlineSample& s =
                track.track.centerline[drivers.autopilot(i).nearest_sample()];
            const glm::dvec3 offset = world.car(i).state().position - s.position;
            result.lowest_m = std::min(result.lowest_m, glm::dot(offset, s.up));
            result.widest_m = std::max(result.widest_m, std::abs(glm::dot(offset, s.left)));
        }
        if (save && !result.snapshot && world.time() >= kSaveAt - 1e-9) {
            result.snapshot = world.save_state();
            result.progress = drivers.progress();
        }
    }
    result.hash = world.state_hash();
    result.fewest_laps = drivers.fewest_laps();
    for (std::size_t i = 0; i < race.cars; ++i)
        result.resets += world.car_resets(i) + drivers.rescues(i);
    return result;
}

void expect_clean(const Race& race, const RaceRun& result) {
    EXPECT_EQ(result.fewest_laps, race.laps) << "a car did not finish";
    EXPECT_EQ(result.resets, 0u);
    EXPECT_GT(result.car_contacts, 0u) << "no car ever touched another";
    EXPECT_LT(result.deepest, 0.05) << "m of car-car penetration";
    EXPECT_GT(result.lowest_m, 0.0) << "a car's centre went below the road";
    // The wall's inner face stands at half the width: a centre of mass a car's half-width
    // (about 1 m) short of it is a car against the wall.
    EXPECT_LT(result.widest_m, 0.5 * test::default_track().track.params.width_m - 1.0)
        << "a car's centre came within a metre of a wall";
}

void expect_clean_and_deterministic(const Race& race) {
    const RaceRun reference = run(race, 1, true);
    expect_clean(race, reference);

    for (const int threads : {2, 4})
        EXPECT_EQ(run(race, threads, false).hash, reference.hash) << threads << " threads";
    ASSERT_TRUE(reference.snapshot);
    EXPECT_EQ(run(race, 2, false, &reference).hash, reference.hash)
        << "resumed at " << kSaveAt << " s";
}

TEST(Race, EightCarsFinishALapCleanlyAndTheSameOnAnyThreads) {
    expect_clean_and_deterministic({8, 1});
}

TEST(Race, TwentyCarsFinishThreeLapsCleanlyAndTheSameOnAnyThreads) {
    expect_clean_and_deterministic({20, 3});
}

// A race of 20 cars over 290 s is chaotic: a change in the last bits of any result (a
// faster formula, another compiler's rounding) gives another race. Each nudge of the grid
// by a nanometre stands for one such change, and each such race must finish clean too, with
// contacts by the thousand (docs/testing.md, "The race's margin"; which nudges failed under
// the old rules depends on the bits of the build).
TEST(Race, TwentyCarsFinishThreeLapsCleanlyFromANudgedGrid) {
    for (const int nanometres : {1, 2, 7}) {
        SCOPED_TRACE(testing::Message() << "grid nudged " << nanometres << " nm");
        const Race race{20, 3, nanometres * 1e-9};
        const RaceRun result = run(race, 2, false);
        expect_clean(race, result);
        EXPECT_GT(result.car_contacts, 1000u) << "car-car contact sub-steps: no longer a race";
    }
}

// A car thrown off the map (as over a wall at speed) is put back on the road in its lane,
// clear of the car beside it, once, and races on from there.
TEST(Race, ACarThatLeavesTheTrackIsRescuedAndRacesOn) {
    const test::TrackWorld& track = test::default_track();
    World world(track.statics, cli::tool_world_settings(), track.trees);
    RaceDrivers drivers(track.track, CarSpec::default_car(), 2);
    drivers.add_cars(world);
    const auto update = [&] {
        drivers.drive(world);
        world.update();
        drivers.after_update(world);
    };
    for (int i = 0; i < 300; ++i) update();
    ASSERT_EQ(drivers.rescues(1), 0u);

    Car& thrown = world.car(1);
    RigidBodyState state = thrown.state();
    const CenterlineSample& left_at = track.track.centerline[drivers.autopilot(1).nearest_sample()];
    state.position += left_at.left * 200.0 + left_at.up * 50.0;
    thrown.set_state(state);
    update();
    EXPECT_EQ(drivers.rescues(1), 1u);
    EXPECT_EQ(drivers.rescues(0), 0u);
    const CenterlineSample& back_at = track.track.centerline[drivers.autopilot(1).nearest_sample()];
    const glm::dvec3 offset = thrown.state().position - back_at.position;
    EXPECT_LT(std::abs(glm::dot(offset, back_at.left) - RaceSettings{}.lane_offset * -1.0), 0.5)
        << "m from its own (right) lane";
    EXPECT_LT(std::abs(glm::dot(offset, back_at.up)), 2.0) << "m above the road";
    EXPECT_GT(glm::distance(thrown.state().position, world.car(0).state().position), 10.0)
        << "put down on the other car";

    const double distance_before = drivers.autopilot(1).distance_along();
    for (int i = 0; i < 500; ++i) update();
    EXPECT_EQ(drivers.rescues(1), 1u) << "it left the track again";
    EXPECT_EQ(world.car_resets(1), 0u);
    EXPECT_GT(drivers.autopilot(1).distance_along() - distance_before, 100.0)
        << "m raced in the 5 s after the rescue";
    EXPECT_EQ(drivers.progress().rescues, (std::vector<std::uint64_t>{0, 1}));
}

}  // namespace
}  // namespace trackphys
