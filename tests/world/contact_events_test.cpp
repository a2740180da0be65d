// World::contact_events (docs/design.md#contact-events): cars that meet begin and end one
// touch, a car driven into a wall hits it with its body, a car rolling on the road hits
// nothing. That the events do not depend on threads is tested with the bumping field of
// world_threads_test.cpp.
#include "trackphys/world/contact_events.hpp"

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

#include "trackphys/world/world.hpp"
#include "world/world_scenes.hpp"

namespace trackphys {
namespace {

RigidBodyState moving(const glm::dvec3& position, const glm::dvec3& velocity) {
    RigidBodyState state;
    state.position = position;
    state.linear_velocity = velocity;
    return state;
}

// Every event of `updates` updates, with the update it came from.
struct EventLog {
    template <typename Event>
    struct At {
        int update;
        Event event;
    };
    std::vector<At<CarTouchBeginEvent>> begins;
    std::vector<At<CarTouchEndEvent>> ends;
    std::vector<At<BodyHitEvent>> hits;

    void run(World& world, int updates) {
        for (int u = 0; u < updates; ++u) {
            world.update();
            const ContactEvents events = world.contact_events();
            for (const CarTouchBeginEvent& e : events.car_touch_begins) begins.push_back({u, e});
            for (const CarTouchEndEvent& e : events.car_touch_ends) ends.push_back({u, e});
            for (const BodyHitEvent& e : events.body_hits) hits.push_back({u, e});
        }
    }
};

// Cars 1 and 2 meet head on at 10 m/s each in free space, car 0 is far away: one begin, at
// the closing speed, then one end once they have bounced apart.
TEST(ContactEvents, TwoCarsDrivenIntoEachOtherBeginAndEndOnce) {
    WorldSettings settings;
    settings.gravity = glm::dvec3(0.0);
    World world(std::make_shared<StaticWorld>(), settings);
    CarSpec spec = CarSpec::default_car();
    spec.air_density = 0.0;  // only the contact slows them
    world.add_car(spec, moving({100.0, 0.0, 0.0}, {0.0, 0.0, 10.0}));
    world.add_car(spec, moving({0.0, 0.0, 0.0}, {0.0, 0.0, 10.0}));
    world.add_car(spec, moving({0.0, 0.0, 8.0}, {0.0, 0.0, -10.0}));

    EventLog log;
    log.run(world, 200);
    ASSERT_EQ(log.begins.size(), 1u);
    const CarTouchBeginEvent& begin = log.begins[0].event;
    EXPECT_EQ(begin.car_a, 1u);
    EXPECT_EQ(begin.car_b, 2u);
    EXPECT_NEAR(begin.approach_speed, 20.0, 1.0);
    EXPECT_LT(begin.normal.z, -0.9) << "moving car 1 back along -Z separates them";
    EXPECT_GT(begin.depth, 0.0);
    EXPECT_LT(begin.depth, 0.02) << "a first touch, not a deep overlap";
    EXPECT_GT(begin.point.z, 0.0);
    EXPECT_LT(begin.point.z, 8.0);

    ASSERT_EQ(log.ends.size(), 1u);
    const CarTouchEndEvent& end = log.ends[0].event;
    EXPECT_EQ(end.car_a, 1u);
    EXPECT_EQ(end.car_b, 2u);
    EXPECT_GE(log.ends[0].update, log.begins[0].update);
    EXPECT_GE(end.deepest, begin.depth);
    EXPECT_TRUE(log.hits.empty()) << "there is nothing static to hit";
    EXPECT_LT(world.car(1).state().linear_velocity.z, 0.0) << "the cars bounced apart";
}

// The ground and a wall across the car's path, as colliders 0 and 1: the car hits the wall
// with its body at about its speed.
TEST(ContactEvents, ACarIntoAWallHitsIt) {
    auto statics = std::make_shared<StaticWorld>();
    statics->add(std::make_shared<StaticCollider>(test::flat_grid(200.0, 100)));
    statics->add(std::make_shared<StaticCollider>(test::wall(20.0, 20.0, 3.0)));
    World world(statics);
    const CarSpec spec = CarSpec::default_car();
    world.add_car(spec, moving({0.0, spec.lowest_point_depth() + 0.001, 0.0}, {0.0, 0.0, 15.0}));

    EventLog log;
    log.run(world, 300);
    ASSERT_FALSE(log.hits.empty()) << "the car never hit the wall";
    const BodyHitEvent& hit = log.hits.front().event;
    EXPECT_EQ(hit.car, 0u);
    EXPECT_EQ(spec.ellipsoids[hit.ellipsoid].role, EllipsoidRole::body);
    EXPECT_EQ(hit.triangle.collider, 1u) << "the wall, not the ground";
    EXPECT_LT(hit.triangle.triangle, 2u);
    EXPECT_LT(hit.normal.z, -0.99);
    EXPECT_NEAR(hit.point.z, 20.0, 0.05);
    EXPECT_GT(hit.depth, 0.0);
    // Rolling friction and drag slow it a little over the 1.3 s to the wall.
    EXPECT_GT(hit.approach_speed, 12.0);
    EXPECT_LE(hit.approach_speed, 15.0);
    for (const auto& later : log.hits) EXPECT_EQ(later.event.triangle.collider, 1u);
}

// A car with two bumper balls (one 0.5 mm further out) driven into a still car: the begin's
// approach speed is the closing speed along its normal, as the cars moved before any pair of
// that sub-step pushed them (the first ball's push must not slow the second's reading).
TEST(ContactEvents, TheApproachSpeedIsTakenBeforeTheSubStepsPushes) {
    CarSpec spec = CarSpec::default_car();
    spec.air_density = 0.0;
    CarSpec bumpers = spec;
    bumpers.ellipsoids.push_back(
        {{0.4, 0.05, 2.5}, {0.2, 0.2, 0.2}, {1.0, 0.0, 0.0, 0.0}, EllipsoidRole::body});
    bumpers.ellipsoids.push_back(
        {{-0.4, 0.05, 2.5005}, {0.2, 0.2, 0.2}, {1.0, 0.0, 0.0, 0.0}, EllipsoidRole::body});
    for (const double gap : {0.0001, 0.0013, 0.0031, 0.0057}) {
        WorldSettings settings;
        settings.gravity = glm::dvec3(0.0);
        World world(std::make_shared<StaticWorld>(), settings);
        const double closing = 80.0;
        world.add_car(spec, moving({0.0, 0.0, -5.0 - gap}, {0.0, 0.0, closing}));
        RigidBodyState turned;
        turned.orientation = glm::dquat(0.0, 0.0, 1.0, 0.0);  // half a turn about +Y
        world.add_car(bumpers, turned);
        EventLog log;
        log.run(world, 50);
        ASSERT_EQ(log.begins.size(), 1u) << "gap " << gap;
        const CarTouchBeginEvent& begin = log.begins[0].event;
        // Car 0 moves along +Z into car 1 at rest: the approach along the normal (moving
        // car 0 along it separates them) is -closing n.z.
        EXPECT_NEAR(begin.approach_speed, -closing * begin.normal.z, 1e-9 * closing)
            << "gap " << gap << ", normal z " << begin.normal.z;
    }
}

// Wheels rolling on the road are no events: a car driving circles on flat ground for 5 s.
TEST(ContactEvents, ACarRollingOnTheRoadHitsNothing) {
    World world(test::static_world_of(test::flat_grid(400.0, 40)));
    const CarSpec spec = CarSpec::preset("gt");
    world.add_car(spec, moving({0.0, spec.lowest_point_depth() + 0.001, 0.0}, {0.0, 0.0, 5.0}));
    world.car(0).set_inputs({1.0, 0.0, 0.3});

    std::uint64_t wheel_contacts = 0;
    for (int u = 0; u < 500; ++u) {
        world.update();
        wheel_contacts += world.last_profile().contacts;
        EXPECT_TRUE(world.contact_events().body_hits.empty()) << "update " << u;
    }
    EXPECT_GT(wheel_contacts, 0u) << "the wheels never touched the road";
    EXPECT_GT(glm::length(world.car(0).state().linear_velocity), 10.0) << "the car drove";
}

}  // namespace
}  // namespace trackphys
