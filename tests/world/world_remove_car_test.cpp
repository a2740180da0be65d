// World::remove_car: the cars after the removed one move down an index and keep every bit of
// their state; a world goes on updating without the car; a snapshot afterwards resumes in a
// world of the remaining cars, one from before is refused. (Thread counts:
// world_threads_test.cpp.)
#include <cstdint>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tool_world_settings.hpp"
#include "trackphys/error.hpp"
#include "trackphys/world/world.hpp"
#include "trackphys/world/world_snapshot.hpp"
#include "world/world_scenes.hpp"

namespace trackphys {
namespace {

// Cars of these presets in a row across flat ground, 4 m apart, each with its own inputs.
World row_of(const std::vector<std::string>& presets) {
    World world(test::static_world_of(test::flat_grid(400.0, 40)), cli::tool_world_settings());
    for (const std::string& preset : presets) {
        const CarSpec spec = CarSpec::preset(preset);
        const double k = static_cast<double>(world.car_count());
        RigidBodyState state;
        state.position = {4.0 * k - 6.0, spec.lowest_point_depth() + 0.001, -150.0};
        const std::size_t car = world.add_car(spec, state);
        world.car(car).set_inputs({0.5 + 0.1 * k, 0.0, 0.1 * k - 0.15});
    }
    return world;
}

void run(World& world, int updates) {
    for (int u = 0; u < updates; ++u) world.update();
}

bool same_state(const RigidBodyState& a, const RigidBodyState& b) {
    return a.position == b.position && a.orientation == b.orientation &&
           a.linear_velocity == b.linear_velocity && a.angular_velocity == b.angular_velocity;
}

TEST(WorldRemoveCar, LaterCarsMoveDownAndKeepTheirState) {
    World world = row_of({"arcade", "gt", "arcade", "formula"});
    run(world, 30);
    std::vector<RigidBodyState> states;
    for (std::size_t i = 0; i < world.car_count(); ++i) states.push_back(world.car(i).state());
    const std::vector<Contact> contacts(world.contacts(3).begin(), world.contacts(3).end());
    const double time = world.time();

    world.remove_car(1);
    ASSERT_EQ(world.car_count(), 3u);
    EXPECT_TRUE(same_state(world.car(0).state(), states[0]));
    EXPECT_TRUE(same_state(world.car(1).state(), states[2]));
    EXPECT_TRUE(same_state(world.car(2).state(), states[3]));
    EXPECT_NE(world.car(2).vehicle(), nullptr) << "the formula car moved down to 2";
    EXPECT_EQ(world.contacts(2).size(), contacts.size());
    EXPECT_EQ(world.contacts(2)[0].depth, contacts[0].depth);
    EXPECT_EQ(world.time(), time);
    EXPECT_THROW(world.remove_car(3), Error);

    run(world, 30);
    EXPECT_GT(world.car(2).state().position.z, states[3].position.z) << "it drives on";
    world.remove_car(2);
    world.remove_car(0);
    world.remove_car(0);
    EXPECT_EQ(world.car_count(), 0u);
    run(world, 1);
    EXPECT_EQ(world.update_count(), 61u);
}

// A removal and an add_car of a car with more ellipsoids leave the car count as it was: the
// next update must still size the workers' scratch for the new car.
TEST(WorldRemoveCar, ACarAddedAfterARemovalUpdates) {
    World world = row_of({"arcade", "arcade"});
    run(world, 5);
    world.remove_car(0);
    CarSpec bigger = CarSpec::default_car();
    for (int k = 0; k < 4; ++k) {
        CarEllipsoid body = bigger.ellipsoids.back();
        body.center.y += 0.01 * (k + 1);
        bigger.ellipsoids.push_back(body);
    }
    RigidBodyState state;
    state.position = {10.0, bigger.lowest_point_depth() + 0.001, -150.0};
    world.add_car(bigger, state);
    ASSERT_EQ(world.car_count(), 2u);
    run(world, 20);
    EXPECT_EQ(world.car_resets(1), 0u);
    EXPECT_LT(world.contacts(1)[0].depth, 0.05);
}

TEST(WorldRemoveCar, SnapshotAfterARemovalResumesInAWorldOfTheRemainingCars) {
    World world = row_of({"arcade", "gt", "arcade"});
    run(world, 30);
    const WorldSnapshot before = world.save_state();
    world.remove_car(0);
    const WorldSnapshot after = world.save_state();
    EXPECT_EQ(after.cars.size(), 2u);
    EXPECT_THROW(world.restore_state(before), Error);
    run(world, 30);

    World resumed = row_of({"gt", "arcade"});
    resumed.restore_state(after);
    run(resumed, 30);
    EXPECT_EQ(resumed.state_hash(), world.state_hash());
}

}  // namespace
}  // namespace trackphys
