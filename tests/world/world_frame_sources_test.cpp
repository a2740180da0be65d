// Where the plane trees get their triangles' frames is a memory-for-speed choice that must
// not show in the results: a race on trees that keep their frames (a world within the
// frame budget) and on trees whose queries build them (a map too big to keep them) ends in
// the same state, bit for bit.
#include <cstdint>

#include <gtest/gtest.h>

#include "trackphys/world/race_drivers.hpp"
#include "trackphys/world/world.hpp"
#include "world/track_world.hpp"

namespace trackphys {
namespace {

std::uint64_t race_state_hash(std::size_t frame_budget_bytes, bool expect_kept) {
    constexpr std::size_t kCars = 8;
    constexpr int kUpdates = 600;  // 6 s from the grid, where the field is close together
    const test::TrackWorld& track = test::default_track();
    const ColliderPlaneTrees trees = make_collider_plane_trees(
        *track.statics, PlaneTreeSettings::precomputed(), 0, frame_budget_bytes);
    EXPECT_EQ(trees.front()->keeps_frames(), expect_kept);
    WorldSettings settings;
    settings.threads = 2;
    World world(track.statics, settings, trees);
    RaceDrivers drivers(track.track, CarSpec::default_car(), kCars);
    drivers.add_cars(world);
    for (int u = 0; u < kUpdates; ++u) {
        drivers.drive(world);
        world.update();
        drivers.after_update(world);
    }
    return world.state_hash();
}

TEST(WorldFrameSources, KeptAndBuiltFramesRaceToTheSameState) {
    EXPECT_EQ(race_state_hash(kPlaneTreeFrameBudget, true), race_state_hash(0, false));
}

}  // namespace
}  // namespace trackphys
