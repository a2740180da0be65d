// World::contact_events (docs/design.md#contact-events): cars that meet begin and end one
// touch, a car driven into a wall hits it with its body, a car rolling on the road hits
// nothing. That the events do not depend on threads is tested with the bumping field of
// world_threads_test.cpp.
#include "trackphys/world/contact_events.hpp"

#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

#include "core/fnv1a.hpp"
#include "support/error_message.hpp"
#include "trackphys/world/world.hpp"
#include "world/world_scenes.hpp"

namespace trackphys {
namespace {

using test::moving;
using test::one_car_pushing_a_braked_one;

// No static world and no gravity: cars meet only each other.
World world_in_free_space() {
    WorldSettings settings;
    settings.gravity = glm::dvec3(0.0);
    return World(std::make_shared<StaticWorld>(), settings);
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

    // Every car touch event with its update, bit for bit.
    std::uint64_t touches_hash() const {
        core::Fnv1a hash;
        for (const auto& [u, e] : begins) {
            hash.add(static_cast<std::uint64_t>(u)),
                hash.add(std::uint64_t{e.car_a} << 32 | e.car_b);
            hash.add(e.point), hash.add(e.normal), hash.add(e.depth), hash.add(e.approach_speed);
        }
        for (const auto& [u, e] : ends) {
            hash.add(static_cast<std::uint64_t>(u)),
                hash.add(std::uint64_t{e.car_a} << 32 | e.car_b);
            hash.add(e.deepest);
        }
        return hash.value;
    }
};

// Updates `world` until a pair of cars is touching at the end of an update.
WorldSnapshot run_until_touching(World& world) {
    for (int u = 0; u < 1000; ++u) {
        world.update();
        if (WorldSnapshot now = world.save_state(); !now.touching.empty()) return now;
    }
    ADD_FAILURE() << "the cars never touched";
    return world.save_state();
}

// Cars 1 and 2 meet head on at 10 m/s each in free space, car 0 is far away: one begin, at
// the closing speed, then one end once they have bounced apart.
TEST(ContactEvents, TwoCarsDrivenIntoEachOtherBeginAndEndOnce) {
    World world = test::head_on_in_free_space();  // no air drag: only the contact slows them

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

// A snapshot taken while one car pushes the other: the original run, a fresh world restored
// from it and the same world rolled back to it give the same events (no second begin for
// the pair in contact, the same end), since the snapshot holds which pairs are touching.
TEST(ContactEvents, ARestoredOrRolledBackWorldGivesTheOriginalEvents) {
    World original = one_car_pushing_a_braked_one();
    const WorldSnapshot snapshot = run_until_touching(original);
    ASSERT_EQ(snapshot.touching.size(), 1u);
    EXPECT_EQ(snapshot.touching[0].car_a, 0u);
    EXPECT_EQ(snapshot.touching[0].car_b, 1u);
    EXPECT_GT(snapshot.touching[0].deepest, 0.0);
    EventLog first;
    first.run(original, 300);
    ASSERT_FALSE(first.begins.empty()) << "the cars bounce and meet again";
    EXPECT_GT(first.begins[0].update, 0) << "the touch of the snapshot went on";
    const std::uint64_t state = original.state_hash();

    World restored = one_car_pushing_a_braked_one();
    restored.restore_state(snapshot);
    EventLog after_restore;
    after_restore.run(restored, 300);
    EXPECT_EQ(restored.state_hash(), state);
    EXPECT_EQ(after_restore.begins.size(), first.begins.size());
    EXPECT_EQ(after_restore.ends.size(), first.ends.size());
    EXPECT_EQ(after_restore.touches_hash(), first.touches_hash());

    original.restore_state(snapshot);
    EventLog after_rollback;
    after_rollback.run(original, 300);
    EXPECT_EQ(original.state_hash(), state);
    EXPECT_EQ(after_rollback.touches_hash(), first.touches_hash());
}

// A rollback to before the touch, from a world where the pair is touching: the events follow
// the restored state (nothing touching), so no end for the pair, and its touch begins again
// where the original's began.
TEST(ContactEvents, ARollbackToBeforeATouchBeginsItAgainWhereItBegan) {
    World world = one_car_pushing_a_braked_one();
    const WorldSnapshot apart = world.save_state();
    EventLog first;
    int updates = 0;
    while (world.save_state().touching.empty() && updates < 1000) first.run(world, 1), ++updates;
    ASSERT_EQ(first.begins.size(), 1u);

    world.restore_state(apart);
    EXPECT_TRUE(world.save_state().touching.empty());
    EventLog again;
    for (int u = 0; u < updates; ++u) again.run(world, 1);
    EXPECT_TRUE(again.ends.empty());
    EXPECT_EQ(again.touches_hash(), first.touches_hash());
}

// A touching list that is not pairs of the world's cars in (car_a, car_b) order, each once
// with a finite non-negative deepest overlap, is refused naming the problem, and the world
// stays as it was.
TEST(ContactEvents, ABadTouchingListIsRefused) {
    World world = one_car_pushing_a_braked_one();
    const WorldSnapshot good = run_until_touching(world);
    const std::uint64_t state = world.state_hash();
    const auto refusal = [&](std::vector<CarTouchSnapshot> touching) {
        WorldSnapshot bad = good;
        bad.touching = std::move(touching);
        return test::error_of([&] { world.restore_state(bad); });
    };
    const double nan = std::numeric_limits<double>::quiet_NaN();
    EXPECT_NE(refusal({{1, 0, 0.01}}).find("touching pair 0 (cars 1, 0): car_a is not below car_b"),
              std::string::npos);
    EXPECT_NE(refusal({{0, 0, 0.01}}).find("car_a is not below car_b"), std::string::npos);
    EXPECT_NE(refusal({{0, 2, 0.01}}).find("touching pair 0 (cars 0, 2): the snapshot has 2 cars"),
              std::string::npos);
    EXPECT_NE(refusal({{0, 1, 0.01}, {0, 1, 0.02}}).find("touching pair 1 (cars 0, 1): not after"),
              std::string::npos);
    EXPECT_NE(refusal({{0, 1, -0.01}}).find("deepest is not finite and >= 0"), std::string::npos);
    EXPECT_NE(refusal({{0, 1, nan}}).find("deepest is not finite and >= 0"), std::string::npos);
    EXPECT_EQ(world.state_hash(), state);
    EXPECT_EQ(world.save_state().touching, good.touching) << "a refusal changes nothing";
    EXPECT_EQ(good.validate(), "");
}

// Car 1's absurd air density (1e300 kg/m^3) turns its state NaN as soon as the overlap with
// car 0 pushes it, so it is reset to where each update began, at rest, overlapping car 0
// again: its touches of the undone update are dropped like its hits, so the pair never
// begins and is never listed as touching.
TEST(ContactEvents, AResetCarTouchesNothingOfTheUndoneUpdate) {
    World world = world_in_free_space();
    CarSpec absurd = CarSpec::default_car();
    absurd.air_density = 1e300;
    world.add_car(CarSpec::default_car(), moving(glm::dvec3(0.0), glm::dvec3(0.0)));
    world.add_car(absurd, moving({0.0, 0.0, 20.0}, glm::dvec3(0.0)));
    world.car(1).set_state(moving({0.0, 0.0, 3.5}, glm::dvec3(0.0)));  // into car 0: unchecked
    for (int u = 1; u <= 5; ++u) {
        world.update();
        ASSERT_EQ(world.car_resets(1), static_cast<std::uint64_t>(u)) << "car 1 is reset";
        EXPECT_TRUE(world.contact_events().car_touch_begins.empty()) << "update " << u;
        EXPECT_TRUE(world.save_state().touching.empty()) << "update " << u;
    }
    EXPECT_EQ(world.car_resets(0), 0u);
}

// The ground and a wall across +Z at z = 20 m, as colliders 0 and 1, and a default car on
// the ground at the origin rolling towards the wall at `speed`.
World car_towards_a_wall(double speed) {
    auto statics = std::make_shared<StaticWorld>();
    statics->add(std::make_shared<StaticCollider>(test::flat_grid(200.0, 100)));
    statics->add(std::make_shared<StaticCollider>(test::wall(20.0, 20.0, 3.0)));
    World world(statics);
    const CarSpec spec = CarSpec::default_car();
    world.add_car(spec, moving({0.0, spec.lowest_point_depth() + 0.001, 0.0}, {0.0, 0.0, speed}));
    return world;
}

// The car hits the wall with its body at about its speed.
TEST(ContactEvents, ACarIntoAWallHitsIt) {
    World world = car_towards_a_wall(15.0);
    const CarSpec& spec = world.car(0).spec();

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

// A car pressed into a wall, its body touching it at the end of an update: the touch goes on
// without a new hit, but a teleport to where it still touches starts it afresh, and the
// next update hits the wall again, as after a reset. (Eased back to 1 cm into the wall and
// lifted by 5 cm: pressed by full throttle, the body and the squatting rear wheels are deeper
// than a teleport accepts.)
TEST(ContactEvents, ATeleportedCarHitsAfresh) {
    World world = car_towards_a_wall(5.0);
    const CarSpec& spec = world.car(0).spec();
    world.car(0).set_inputs({1.0, 0.0, 0.0});
    const auto touching_body = [&]() -> std::size_t {
        for (std::size_t e = 0; e < spec.ellipsoids.size(); ++e)
            if (spec.ellipsoids[e].role == EllipsoidRole::body && world.contacts(0)[e].depth > 0.0)
                return e;
        return spec.ellipsoids.size();
    };
    int updates = 0;
    while (touching_body() == spec.ellipsoids.size() && updates++ < 1000) world.update();
    const std::size_t pressed = touching_body();
    ASSERT_LT(pressed, spec.ellipsoids.size()) << "the car never pressed into the wall";
    const WorldSnapshot against_the_wall = world.save_state();
    const auto hits_of_pressed = [&] {
        std::size_t count = 0;
        for (const BodyHitEvent& hit : world.contact_events().body_hits)
            count += hit.ellipsoid == pressed;
        return count;
    };

    world.update();
    ASSERT_GT(world.contacts(0)[pressed].depth, 0.0) << "the touch should go on";
    EXPECT_EQ(hits_of_pressed(), 0u) << "a touch that goes on is no new hit";

    world.restore_state(against_the_wall);
    RigidBodyState eased = world.car(0).state();
    eased.position.y += 0.05;                                     // off its squatting rear wheels
    eased.position.z -= world.contacts(0)[pressed].depth - 0.01;  // 1 cm into the wall
    world.teleport_car(0, eased);
    EXPECT_EQ(world.contacts(0)[pressed].depth, -std::numeric_limits<double>::infinity())
        << "a teleported car has no contacts until its next update";
    world.update();
    EXPECT_EQ(hits_of_pressed(), 1u) << "the teleported car hits the wall afresh";
}

// Car 0 leaves the world: the events after it name the cars by their new indices, a touch of
// the removed car ends without an event, and the others' touches go on.
TEST(ContactEvents, EventsAfterARemovalNameTheCarsByTheirNewIndices) {
    World world = world_in_free_space();
    CarSpec spec = CarSpec::default_car();
    spec.air_density = 0.0;
    world.add_car(spec, moving({0.0, 0.0, 14.0}, {0.0, 0.0, -10.0}));
    world.add_car(spec, moving({0.0, 0.0, 8.0}, glm::dvec3(0.0)));
    world.add_car(spec, moving({50.0, 0.0, 0.0}, {0.0, 0.0, 10.0}));
    world.add_car(spec, moving({50.0, 0.0, 16.0}, {0.0, 0.0, -10.0}));
    const WorldSnapshot first_touch = run_until_touching(world);
    ASSERT_EQ(first_touch.touching.size(), 1u);
    EXPECT_EQ(first_touch.touching[0].car_a, 0u);
    EXPECT_EQ(first_touch.touching[0].car_b, 1u);

    world.remove_car(0);  // in the middle of its touch with car 1, now car 0
    EXPECT_TRUE(world.save_state().touching.empty());
    EventLog log;
    log.run(world, 100);
    for (const auto& end : log.ends)
        EXPECT_NE(end.event.car_a, 0u) << "the removed car's touch ended without an event";
    ASSERT_EQ(log.begins.size(), 1u) << "only cars 2 and 3, now 1 and 2, meet";
    EXPECT_EQ(log.begins[0].event.car_a, 1u);
    EXPECT_EQ(log.begins[0].event.car_b, 2u);
    ASSERT_EQ(log.ends.size(), 1u);
    EXPECT_EQ(log.ends[0].event.car_a, 1u);
    EXPECT_EQ(log.ends[0].event.car_b, 2u);
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
        World world = world_in_free_space();
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
