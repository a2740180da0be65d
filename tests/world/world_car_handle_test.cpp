// World::car(i), the handle a game holds: what a game does to a car (inputs, a teleport, a
// vehicle state, road grip, an impulse) goes through it and leaves the world valid; what only
// World::update and restore_state do (a sub-step, a restore, replacing the car) does not
// compile through it (Car's and Vehicle's class notes).
#include <cstddef>
#include <span>
#include <type_traits>

#include <gtest/gtest.h>

#include <glm/vec3.hpp>

#include "trackphys/dynamics/car.hpp"
#include "trackphys/vehicle/vehicle.hpp"
#include "trackphys/world/world.hpp"
#include "trackphys/world/world_snapshot.hpp"
#include "world/world_scenes.hpp"

namespace trackphys {
namespace {

// Each concept asks whether a game's code could make the call on the handle's type.
template <class C>
concept CanAdvance = requires(C& car, std::span<const Contact> deepest, glm::dvec3 gravity) {
    car.advance(deepest, gravity, 0.001);
};
template <class C>
concept CanRestore = requires(C& car, RigidBodyState state, std::span<const double> travel) {
    car.restore(state, CarInputs{}, travel);
};
template <class C>
concept CanSetSuspension = requires(C& car, std::span<const double> travel) {
    car.set_suspension(travel);
};
template <class C>
concept CanShareEllipsoids = requires(C& car, const C& other) {
    car.share_ellipsoids_with(other);
};
template <class C>
concept CanPlaceEllipsoid = requires(const C& car, PlacingRotation rotation, Ellipsoid& placed) {
    car.place_ellipsoid(std::size_t{0}, rotation, placed);
};
template <class V>
concept CanStepVehicle = requires(V& vehicle, std::span<const double> travel) {
    vehicle.begin_substep(0.0, 0.0, 0.0, 0.0, 0.001);
    vehicle.wheel_force(std::size_t{0}, 0.0, 0.0, 0.0, 0.001);
    vehicle.measure_anti_roll(travel);
};
template <class V>
concept CanSetRoadGrip = requires(V& vehicle) {
    vehicle.set_road_grip(std::size_t{0}, 0.5);
};

using Handle = decltype(std::declval<World&>().car(0));

TEST(WorldCarHandle, CannotReplaceTheCar) {
    EXPECT_FALSE((std::is_assignable_v<Handle, const Car&>));
    EXPECT_FALSE((std::is_assignable_v<Handle, Car&&>));
    EXPECT_TRUE(std::is_copy_constructible_v<Car>) << "a game may keep its own copy";
}

TEST(WorldCarHandle, CannotRunTheWorldsSteps) {
    using C = std::remove_reference_t<Handle>;
    EXPECT_FALSE(CanAdvance<C>);
    EXPECT_FALSE(CanRestore<C>);
    EXPECT_FALSE(CanSetSuspension<C>);
    EXPECT_FALSE(CanShareEllipsoids<C>);
    EXPECT_FALSE(CanPlaceEllipsoid<C>);
    using V = std::remove_pointer_t<decltype(std::declval<C&>().vehicle())>;
    EXPECT_FALSE(CanStepVehicle<V>);
    EXPECT_TRUE(CanSetRoadGrip<V>);
}

TEST(WorldCarHandle, WhatAGameDoesKeepsTheWorldValid) {
    World world(test::static_world_of(test::flat_grid(200.0, 20)));
    for (const char* preset : {"arcade", "gt"}) {
        const CarSpec spec = CarSpec::preset(preset);
        RigidBodyState state;
        state.position = {4.0 * static_cast<double>(world.car_count()),
                          spec.lowest_point_depth() + 0.001, 0.0};
        world.add_car(spec, state);
    }
    for (int u = 0; u < 20; ++u) world.update();

    Car& arcade = world.car(0);
    arcade.set_inputs({0.8, 0.0, 0.2});
    arcade.apply_impulse({0.0, 0.0, 500.0}, arcade.state().position);
    Car& gt = world.car(1);
    RigidBodyState moved = gt.state();
    moved.position.z += 20.0;
    gt.set_state(moved);
    gt.set_vehicle_state(gt.vehicle()->at_rest());
    gt.vehicle()->set_road_grip(0, 0.5);
    for (int u = 0; u < 20; ++u) world.update();

    EXPECT_EQ(world.save_state().validate(), "");
    EXPECT_EQ(world.update_count(), 40u);
    EXPECT_GT(world.car(0).state().linear_velocity.z, 0.0);
    EXPECT_EQ(world.car_resets(0) + world.car_resets(1), 0u);
}

}  // namespace
}  // namespace trackphys
