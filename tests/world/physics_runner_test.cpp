// PhysicsRunner: stamped inputs replay bit-identically, the published pair of states (poses
// and views) is the world's and interpolates between its ends, and a render thread reads it
// while the physics thread runs (these tests also run under ThreadSanitizer:
// scripts/test_tsan.sh).
#include "trackphys/world/physics_runner.hpp"

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

#include "support/error_message.hpp"
#include "tool_world_settings.hpp"
#include "trackphys/error.hpp"
#include "trackphys/world/job_system.hpp"
#include "trackphys/world/world.hpp"
#include "world/world_scenes.hpp"

namespace trackphys {
namespace {

// Two cars side by side on flat ground (two islands: their boxes are 4 m apart).
World two_cars(const CarSpec& spec = CarSpec::default_car(),
               const WorldSettings& settings = cli::tool_world_settings()) {
    World world(test::static_world_of(test::flat_grid(400.0, 40)), settings);
    for (const double x : {-3.0, 3.0}) {
        RigidBodyState state;
        state.position = {x, spec.lowest_point_depth() + 0.001, -150.0};
        world.add_car(spec, state);
    }
    return world;
}

// The stream: car 0 accelerates and steers at update 5, car 1 brakes in at 30 and 31.
struct Stamped {
    std::uint64_t update;
    std::size_t car;
    CarInputs inputs;
};
const std::vector<Stamped> kStream = {{1, 0, {1.0, 0.0, 0.0}},   {1, 1, {0.8, 0.0, 0.0}},
                                      {5, 0, {1.0, 0.0, 0.3}},   {30, 1, {0.0, 0.5, 0.0}},
                                      {31, 1, {0.0, 1.0, -0.2}}, {60, 0, {0.2, 0.0, 0.0}}};
constexpr std::uint64_t kUpdates = 80;

std::uint64_t direct_replay() {
    World world = two_cars();
    for (std::uint64_t update = 1; update <= kUpdates; ++update) {
        for (const Stamped& s : kStream)
            if (s.update == update) world.car(s.car).set_inputs(s.inputs);
        world.update();
    }
    return world.state_hash();
}

TEST(PhysicsRunner, StampedInputsGiveTheHashOfADirectReplay) {
    PhysicsRunner runner(two_cars(), false);
    // Given in another order than they apply: the stamp decides.
    for (auto s = kStream.rbegin(); s != kStream.rend(); ++s)
        runner.set_inputs(s->update, s->car, s->inputs);
    runner.run_to(kUpdates);
    runner.wait();
    EXPECT_EQ(runner.world().update_count(), kUpdates);
    EXPECT_EQ(runner.world().state_hash(), direct_replay());
    EXPECT_EQ(runner.late_inputs(), 0u);
    EXPECT_EQ(runner.published_update(), kUpdates);
}

// The game thread gives the stream's later inputs while the physics thread runs in real
// time (each 20 updates, 200 ms, before its stamp, by its own clock: published_update() is
// the render thread's) and a render thread reads: the inputs' mutex under contention
// (ThreadSanitizer), and still the direct replay's bits.
TEST(PhysicsRunner, InputsGivenWhileTheThreadRunsReplayBitForBit) {
    constexpr std::uint64_t kAhead = 20;
    PhysicsRunner runner(two_cars(), true);
    const double dt = runner.world().settings().dt_update;
    for (const Stamped& s : kStream)
        if (s.update <= kAhead) runner.set_inputs(s.update, s.car, s.inputs);
    std::atomic<bool> done{false};
    bool finite = true;
    std::thread render([&] {
        while (!done.load()) {
            const CarPose pose =
                runner.pose(1, 0.01 * static_cast<double>(runner.published_update()));
            finite = finite && std::isfinite(pose.position.z);
        }
    });
    const auto started = std::chrono::steady_clock::now();
    runner.run_to(kUpdates);
    for (const Stamped& s : kStream) {
        if (s.update <= kAhead) continue;
        std::this_thread::sleep_until(
            started + std::chrono::duration<double>(dt * static_cast<double>(s.update - kAhead)));
        runner.set_inputs(s.update, s.car, s.inputs);
    }
    runner.wait();
    done.store(true);
    render.join();
    EXPECT_TRUE(finite);
    EXPECT_EQ(runner.late_inputs(), 0u);
    EXPECT_EQ(runner.world().state_hash(), direct_replay());
}

// A game thread follows the physics' progress by latest_update() and takes the kept events
// while a render thread reads (ThreadSanitizer): the update only grows, passes through the
// run, and ends at its last update, where the render thread's frame is; the two cars, apart
// on their wheels, give no event.
TEST(PhysicsRunner, TheGameThreadFollowsTheLatestUpdate) {
    PhysicsRunner runner(two_cars(), true);
    runner.keep_events(true);
    RunnerEvents events;
    std::size_t taken = 0;
    EXPECT_EQ(runner.latest_update(), 0u);
    std::atomic<bool> done{false};
    std::thread render([&] {
        while (!done.load()) static_cast<void>(runner.pose(0, 0.0));
    });
    runner.run_to(kUpdates);
    std::uint64_t last = 0, seen_between = 0;
    bool grows = true;
    while (runner.running()) {
        const std::uint64_t now = runner.latest_update();
        grows = grows && now >= last && now <= kUpdates;
        if (now > 0 && now < kUpdates) ++seen_between;
        last = now;
        runner.take_events(events);
        taken += events.car_touch_begins.size() + events.body_hits.size() + events.resets.size();
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    runner.wait();
    done.store(true);
    render.join();
    EXPECT_TRUE(grows);
    EXPECT_GT(seen_between, 0u);
    EXPECT_EQ(taken, 0u);
    EXPECT_EQ(runner.latest_update(), kUpdates);
    EXPECT_EQ(runner.published_update(), kUpdates);
}

// A render clock that once divides 0 by 0 gets an error, not a NaN pose to draw; infinite
// times are the ends of the published pair.
TEST(PhysicsRunner, ANaNRenderTimeIsAnErrorAndInfiniteOnesAreTheEnds) {
    PhysicsRunner runner(two_cars(), false);
    runner.run_to(3);
    runner.wait();
    const double nan = std::numeric_limits<double>::quiet_NaN();
    EXPECT_EQ(test::error_of([&] { runner.pose(0, nan); }),
              "PhysicsRunner::pose: the render time is NaN");
    EXPECT_EQ(test::error_of([&] { runner.view(0, nan); }),
              "PhysicsRunner::view: the render time is NaN");
    const double inf = std::numeric_limits<double>::infinity();
    EXPECT_EQ(runner.pose(0, inf).position, runner.pose(0, 0.03).position);
    EXPECT_EQ(runner.pose(0, -inf).position, runner.pose(0, 0.02).position);
}

TEST(PhysicsRunner, LateInputsApplyAtTheNextUpdateAndAreCounted) {
    PhysicsRunner runner(two_cars(), false);
    runner.run_to(10);
    runner.wait();
    runner.set_inputs(3, 0, {1.0, 0.0, 0.0});  // update 3 ran already
    runner.run_to(11);
    runner.wait();
    EXPECT_EQ(runner.late_inputs(), 1u);
    EXPECT_EQ(runner.world().car(0).inputs().throttle, 1.0);
    EXPECT_THROW(runner.set_inputs(12, 2, {}), Error);
    EXPECT_THROW(runner.set_inputs(12, 0, {std::nan(""), 0.0, 0.0}), Error);
}

TEST(PhysicsRunner, InterpolatedPoseRunsFromThePreviousStateToTheLast) {
    PhysicsRunner runner(two_cars(), false);
    runner.set_inputs(1, 0, {1.0, 0.0, 0.4});
    runner.run_to(40);
    runner.wait();
    const RigidBodyState before = runner.world().car(0).state();
    const double t0 = runner.world().time();
    runner.run_to(41);
    runner.wait();
    const RigidBodyState after = runner.world().car(0).state();
    const double t1 = runner.world().time();
    ASSERT_GT(glm::length(after.position - before.position), 0.01) << "the car does not move";

    EXPECT_EQ(runner.pose(0, t0).position, before.position);
    EXPECT_EQ(runner.pose(0, t0).orientation, before.orientation);
    EXPECT_EQ(runner.pose(0, t1).position, after.position);
    EXPECT_EQ(runner.pose(0, t1).orientation, after.orientation);
    EXPECT_EQ(runner.pose(0, t0 - 1.0).position, before.position) << "clamped before";
    EXPECT_EQ(runner.pose(0, t1 + 1.0).position, after.position) << "clamped after";
    for (const double share : {0.25, 0.5, 0.75}) {
        const CarPose mid = runner.pose(0, t0 + share * (t1 - t0));
        for (int k = 0; k < 3; ++k) {
            EXPECT_GE(mid.position[k], std::min(before.position[k], after.position[k]));
            EXPECT_LE(mid.position[k], std::max(before.position[k], after.position[k]));
        }
        EXPECT_NEAR(glm::length(mid.position - before.position),
                    share * glm::length(after.position - before.position), 1e-9);
        // The orientation turns by the share of the whole turn.
        const double whole = glm::angle(glm::inverse(before.orientation) * after.orientation);
        const double part = glm::angle(glm::inverse(before.orientation) * mid.orientation);
        EXPECT_NEAR(part, share * whole, 1e-9);
    }
}

// A render thread reading while the physics thread runs in real time: the updates it sees
// only move forward, and every pose is a finite one from the published pairs.
TEST(PhysicsRunner, RenderThreadReadsWhileThePhysicsThreadRuns) {
    PhysicsRunner runner(two_cars(), true);
    runner.set_inputs(1, 0, {1.0, 0.0, 0.0});
    std::atomic<bool> done{false};
    std::uint64_t last_seen = 0;
    bool ordered = true;
    bool finite = true;
    std::thread render([&] {
        while (!done.load()) {
            const std::uint64_t update = runner.published_update();
            ordered = ordered && update >= last_seen;
            last_seen = update;
            const CarPose pose = runner.pose(0, 0.01 * static_cast<double>(update) - 0.005);
            finite = finite && std::isfinite(pose.position.x) && std::isfinite(pose.orientation.w);
        }
    });
    runner.run_to(20);
    runner.wait();
    done.store(true);
    render.join();
    EXPECT_TRUE(ordered);
    EXPECT_TRUE(finite);
    EXPECT_EQ(runner.published_update(), 20u);
    EXPECT_GT(runner.world().car(0).state().position.z, -150.0);
}

// Every field of two views bit for bit.
void expect_same_view(const CarView& a, const CarView& b) {
    EXPECT_EQ(a.pose.position, b.pose.position);
    EXPECT_EQ(a.pose.orientation, b.pose.orientation);
    EXPECT_EQ(a.linear_velocity, b.linear_velocity);
    EXPECT_EQ(a.angular_velocity, b.angular_velocity);
    EXPECT_EQ(a.engine_rpm, b.engine_rpm);
    EXPECT_EQ(a.gear, b.gear);
    ASSERT_EQ(a.wheels.size(), b.wheels.size());
    for (std::size_t w = 0; w < a.wheels.size(); ++w) {
        EXPECT_EQ(a.wheels[w].ellipsoid, b.wheels[w].ellipsoid);
        EXPECT_EQ(a.wheels[w].position, b.wheels[w].position);
        EXPECT_EQ(a.wheels[w].orientation, b.wheels[w].orientation);
        EXPECT_EQ(a.wheels[w].suspension, b.wheels[w].suspension);
        EXPECT_EQ(a.wheels[w].steer_angle, b.wheels[w].steer_angle);
        EXPECT_EQ(a.wheels[w].spin, b.wheels[w].spin);
        EXPECT_EQ(a.wheels[w].spin_angle, b.wheels[w].spin_angle);
    }
}

// The wheel's orientation relative to the body: steered about +Y, spun about +X.
glm::dquat wheel_in_body(double steer_angle, double spin_angle) {
    return glm::angleAxis(steer_angle, glm::dvec3(0.0, 1.0, 0.0)) *
           glm::angleAxis(spin_angle, glm::dvec3(1.0, 0.0, 0.0));
}

// The arcade car and a vehicle-model car, accelerating and steering left.
class PhysicsRunnerView : public ::testing::TestWithParam<const char*> {
  protected:
    PhysicsRunnerView() : runner_(two_cars(CarSpec::preset(GetParam())), false) {
        runner_.set_inputs(1, 0, {1.0, 0.0, 0.4});
    }
    bool has_vehicle() { return runner_.world().car(0).vehicle() != nullptr; }
    PhysicsRunner runner_;
};

TEST_P(PhysicsRunnerView, PublishedViewIsTheWorldsState) {
    runner_.run_to(60);
    runner_.wait();
    const World& world = runner_.world();
    const Car& car = world.car(0);
    const CarView view = runner_.view(0, world.time());

    EXPECT_EQ(view.pose.position, car.state().position);
    EXPECT_EQ(view.pose.orientation, car.state().orientation);
    EXPECT_EQ(view.linear_velocity, car.state().linear_velocity);
    EXPECT_EQ(view.angular_velocity, car.state().angular_velocity);
    ASSERT_GT(glm::length(view.linear_velocity), 1.0) << "the car does not drive";
    const Vehicle* vehicle = car.vehicle();
    EXPECT_EQ(view.engine_rpm, vehicle ? vehicle->engine_rpm() : 0.0);
    EXPECT_EQ(view.gear, vehicle ? vehicle->state().gear : 0);
    if (vehicle) {
        EXPECT_GT(view.engine_rpm, 0.0);
    }

    ASSERT_EQ(view.wheels.size(), 4u);
    int front = 0;
    for (const WheelView& wheel : view.wheels) {
        const std::size_t i = wheel.ellipsoid;
        ASSERT_LT(i, car.ellipsoid_count());
        const EllipsoidRole role = car.spec().ellipsoids[i].role;
        ASSERT_NE(role, EllipsoidRole::body);
        front += role == EllipsoidRole::front_wheel;
        EXPECT_EQ(wheel.position, car.world_ellipsoid(i).center());
        EXPECT_EQ(wheel.suspension, car.suspension(i));
        EXPECT_GT(wheel.suspension, 0.0) << "the wheel carries no load";
        EXPECT_EQ(wheel.steer_angle, role == EllipsoidRole::front_wheel ? car.steer_angle() : 0.0);
        const double spin = vehicle ? vehicle->state().wheels[vehicle->wheel_slot(i)].spin : 0.0;
        EXPECT_EQ(wheel.spin, spin);
        if (vehicle) {
            EXPECT_GT(wheel.spin_angle, 1.0) << "the wheel has not turned";
        }
        const glm::dquat in_body = glm::inverse(view.pose.orientation) * wheel.orientation;
        const glm::dquat expected = wheel_in_body(wheel.steer_angle, wheel.spin_angle);
        EXPECT_NEAR(std::abs(glm::dot(in_body, expected)), 1.0, 1e-12);
    }
    EXPECT_EQ(front, 2);
    EXPECT_GT(car.steer_angle(), 0.0);
}

TEST_P(PhysicsRunnerView, ViewInterpolatesBetweenThePublishedStates) {
    runner_.run_to(60);
    runner_.wait();
    const double t0 = runner_.world().time();
    const CarView before = runner_.view(0, t0);
    runner_.run_to(61);
    runner_.wait();
    const double t1 = runner_.world().time();
    const CarView after = runner_.view(0, t1);

    expect_same_view(runner_.view(0, t0), before);
    expect_same_view(runner_.view(0, t0 - 1.0), before);
    expect_same_view(runner_.view(0, t1 + 1.0), after);
    // The spin angle advances by the trapezoid of the update's two spins over dt_update (t1 -
    // t0 is that to rounding only).
    const double dt = runner_.world().settings().dt_update;
    for (std::size_t w = 0; w < after.wheels.size(); ++w)
        EXPECT_EQ(after.wheels[w].spin_angle,
                  before.wheels[w].spin_angle +
                      0.5 * (before.wheels[w].spin + after.wheels[w].spin) * dt);

    CarView mid;
    for (const double share : {0.25, 0.5, 0.75}) {
        const double t = t0 + share * (t1 - t0);
        runner_.view(0, t, mid);
        const CarPose pose = runner_.pose(0, t);
        EXPECT_EQ(mid.pose.position, pose.position);
        EXPECT_EQ(mid.pose.orientation, pose.orientation);
        EXPECT_NEAR(mid.engine_rpm,
                    before.engine_rpm + share * (after.engine_rpm - before.engine_rpm), 1e-9);
        EXPECT_NEAR(glm::length(mid.linear_velocity - before.linear_velocity),
                    share * glm::length(after.linear_velocity - before.linear_velocity), 1e-9);
        EXPECT_EQ(mid.gear, after.gear);
        ASSERT_EQ(mid.wheels.size(), after.wheels.size());
        for (std::size_t w = 0; w < mid.wheels.size(); ++w) {
            const WheelView& a = before.wheels[w];
            const WheelView& b = after.wheels[w];
            const WheelView& m = mid.wheels[w];
            EXPECT_NEAR(m.spin_angle, a.spin_angle + share * (b.spin_angle - a.spin_angle), 1e-9);
            EXPECT_NEAR(m.suspension, a.suspension + share * (b.suspension - a.suspension), 1e-12);
            EXPECT_NEAR(glm::length(m.position - a.position),
                        share * glm::length(b.position - a.position), 1e-9);
            const glm::dquat in_body = glm::inverse(mid.pose.orientation) * m.orientation;
            EXPECT_NEAR(std::abs(glm::dot(in_body, wheel_in_body(m.steer_angle, m.spin_angle))),
                        1.0, 1e-12);
        }
    }
}

// A game that runs World::update itself keeps the same views with update_car_view: after
// each update, bit for bit what the runner publishes (spin angles included), and
// interpolate_car_view between two of them is PhysicsRunner::view's.
TEST_P(PhysicsRunnerView, UpdateCarViewIsWhatTheRunnerPublishes) {
    World world = two_cars(CarSpec::preset(GetParam()));
    world.car(0).set_inputs({1.0, 0.0, 0.2});
    runner_.set_inputs(1, 0, {1.0, 0.0, 0.2});
    CarView view, before;
    update_car_view(world.car(0), 0.0, view);  // made for the car, spin angles 0
    const double dt = world.settings().dt_update;
    double before_time = 0.0;
    for (int u = 0; u < 60; ++u) {
        before_time = world.time();
        world.update();
        before = view;
        update_car_view(world.car(0), dt, view);
    }
    runner_.run_to(60);
    runner_.wait();
    const auto bits = [](const CarView& v) {
        std::vector<double> b = {v.pose.position.x,    v.pose.position.y, v.pose.position.z,
                                 v.pose.orientation.w, v.engine_rpm,      double(v.gear)};
        for (const WheelView& w : v.wheels)
            b.insert(b.end(), {w.position.x, w.position.y, w.position.z, w.orientation.x,
                               w.suspension, w.steer_angle, w.spin, w.spin_angle});
        return b;
    };
    EXPECT_EQ(bits(view), bits(runner_.view(0, world.time())));
    // The runner's alpha for a render time between the two updates, as it computes it.
    const double t = world.time() - 0.75 * dt;
    CarView between;
    interpolate_car_view(before, view, (t - before_time) / (world.time() - before_time), between);
    EXPECT_EQ(bits(between), bits(runner_.view(0, t)));
    EXPECT_EQ(test::error_of([&] { interpolate_car_view(before, view, 1.5, between); }),
              "interpolate_car_view: alpha must be in [0, 1], got 1.5");
    EXPECT_EQ(test::error_of([&] { update_car_view(world.car(0), -dt, view); }),
              "update_car_view: dt must be finite and >= 0, got -0.01");
}

INSTANTIATE_TEST_SUITE_P(Presets, PhysicsRunnerView, ::testing::Values("arcade", "gt"));

// A render thread reading views while the physics thread runs a vehicle-model car in real
// time: every view it reads is complete (four wheels, a gear) and finite, and the wheels'
// angles only move forward under full throttle.
TEST(PhysicsRunner, RenderThreadReadsViewsWhileThePhysicsThreadRuns) {
    PhysicsRunner runner(two_cars(CarSpec::preset("gt")), true);
    runner.set_inputs(1, 0, {1.0, 0.0, 0.0});
    std::atomic<bool> done{false};
    bool complete = true;
    bool finite = true;
    bool forward = true;
    double last_angle = 0.0;
    std::thread render([&] {
        CarView view;
        while (!done.load()) {
            const double t = 0.01 * static_cast<double>(runner.published_update()) - 0.005;
            runner.view(0, t, view);
            complete = complete && view.wheels.size() == 4 && view.gear >= 1;
            for (const WheelView& wheel : view.wheels)
                finite = finite && std::isfinite(wheel.position.x) &&
                         std::isfinite(wheel.orientation.w) && std::isfinite(wheel.spin_angle);
            if (view.wheels.empty()) continue;
            forward = forward && view.wheels[0].spin_angle >= last_angle;
            last_angle = view.wheels[0].spin_angle;
        }
    });
    runner.run_to(20);
    runner.wait();
    done.store(true);
    render.join();
    EXPECT_TRUE(complete);
    EXPECT_TRUE(finite);
    EXPECT_TRUE(forward);
    EXPECT_GT(runner.view(0, runner.world().time()).wheels[0].spin_angle, 0.0);
}

TEST(PhysicsRunner, RefusesToRunAWorldWhoseCarsChanged) {
    PhysicsRunner removed(two_cars(), false);
    removed.world().remove_car(1);
    EXPECT_THROW(removed.run_to(1), Error);
    EXPECT_EQ(removed.world().update_count(), 0u);

    // The same count, another car: its views would be read with the old car's wheels.
    PhysicsRunner replaced(two_cars(CarSpec::preset("gt")), false);
    RigidBodyState state = replaced.world().car(0).state();
    state.position.y = CarSpec::default_car().lowest_point_depth() + 0.001;
    replaced.world().remove_car(0);
    replaced.world().add_car(CarSpec::default_car(), state);
    EXPECT_THROW(replaced.run_to(1), Error);
    EXPECT_EQ(replaced.world().update_count(), 0u);
}

TEST(PhysicsRunner, ACarPastThePublishedOnesIsAnErrorNamingBoth) {
    PhysicsRunner runner(two_cars(), false);
    for (const std::string& why : {test::error_of([&] { runner.pose(2, 0.0); }),
                                   test::error_of([&] { runner.view(2, 0.0); }),
                                   test::error_of([&] { runner.set_inputs(1, 2, CarInputs{}); })})
        EXPECT_NE(why.find("no car 2: the runner has 2 cars"), std::string::npos) << why;
}

// Three cars in a row, each with its own throttle.
World three_cars() {
    World world = two_cars();
    const CarSpec spec = CarSpec::default_car();
    RigidBodyState state;
    state.position = {9.0, spec.lowest_point_depth() + 0.001, -150.0};
    world.add_car(spec, state);
    for (std::size_t i = 0; i < 3; ++i)
        world.car(i).set_inputs({0.4 + 0.2 * static_cast<double>(i), 0.0, 0.0});
    return world;
}

// Removing car 1 after 30 updates, then steering car 2 at update 40: the world's bits are a
// direct replay's, the runner keeps numbering car 2 as 2, and car 1 is gone from every call.
TEST(PhysicsRunner, RemoveCarBetweenRunsReplaysADirectRemoval) {
    World direct = three_cars();
    for (int u = 0; u < 30; ++u) direct.update();
    direct.remove_car(1);
    for (std::uint64_t update = 31; update <= 60; ++update) {
        if (update == 40) direct.car(1).set_inputs({1.0, 0.0, 0.3});
        direct.update();
    }

    PhysicsRunner runner(three_cars(), false);
    runner.set_inputs(45, 1, {0.0, 1.0, 0.0});  // pending for the car removed: dropped
    runner.run_to(30);
    runner.wait();
    runner.remove_car(1);
    runner.set_inputs(40, 2, {1.0, 0.0, 0.3});
    runner.run_to(60);
    runner.wait();
    EXPECT_EQ(runner.world().state_hash(), direct.state_hash());
    EXPECT_EQ(runner.world().car_count(), 2u);
    EXPECT_EQ(runner.pose(2, runner.world().time()).position, direct.car(1).state().position);
    for (const std::string& why : {test::error_of([&] { runner.pose(1, 0.0); }),
                                   test::error_of([&] { runner.view(1, 0.0); }),
                                   test::error_of([&] { runner.set_inputs(61, 1, CarInputs{}); }),
                                   test::error_of([&] { runner.remove_car(1); })})
        EXPECT_NE(why.find("car 1 was removed"), std::string::npos) << why;
    runner.start();
    EXPECT_THROW(runner.remove_car(0), Error);
    runner.stop();
}

// The outer two of three cars thrown at each other once the middle one is removed: the
// events a runner keeps are a direct replay's, stamped with their updates and in the
// runner's numbers (its car 2 is the world's 1); a push beyond the limits given between runs
// comes back as a reset; a runner not asked keeps nothing.
TEST(PhysicsRunner, KeptEventsAreADirectReplaysInTheRunnersNumbers) {
    constexpr std::uint64_t kRemoved = 10, kLast = 100;
    const auto thrown = [](World& world) {  // the world's cars 0 and 1, 12 m apart
        for (const auto& [car, vx] : {std::pair{0, 20.0}, std::pair{1, -20.0}}) {
            RigidBodyState state = world.car(car).state();
            state.linear_velocity = {vx, 0.0, 0.0};
            world.car(car).set_state(state);
        }
    };
    World direct = three_cars();
    for (std::uint64_t u = 0; u < kRemoved; ++u) direct.update();
    direct.remove_car(1);
    thrown(direct);
    RunnerEvents expected;
    const auto runner_number = [](std::uint32_t world_car) { return world_car == 0 ? 0u : 2u; };
    for (std::uint64_t u = kRemoved; u < kLast; ++u) {
        direct.update();
        const ContactEvents events = direct.contact_events();
        for (CarTouchBeginEvent e : events.car_touch_begins) {
            e.car_a = runner_number(e.car_a);
            e.car_b = runner_number(e.car_b);
            expected.car_touch_begins.push_back({u + 1, e});
        }
        for (CarTouchEndEvent e : events.car_touch_ends) {
            e.car_a = runner_number(e.car_a);
            e.car_b = runner_number(e.car_b);
            expected.car_touch_ends.push_back({u + 1, e});
        }
        for (BodyHitEvent e : events.body_hits) {
            e.car = runner_number(e.car);
            expected.body_hits.push_back({u + 1, e});
        }
    }
    ASSERT_FALSE(expected.car_touch_begins.empty()) << "the cars must meet";

    PhysicsRunner runner(three_cars(), false);
    runner.keep_events(true);
    runner.run_to(kRemoved);
    runner.wait();
    RunnerEvents before;
    runner.take_events(before);  // the first updates' (none between the cars)
    runner.remove_car(1);
    thrown(runner.world());
    runner.run_to(kLast);
    runner.wait();
    RunnerEvents kept;
    runner.take_events(kept);
    const auto bits = [](const auto& x) {
        return std::vector<char>(reinterpret_cast<const char*>(&x),
                                 reinterpret_cast<const char*>(&x) + sizeof x);
    };
    const auto same = [&](const auto& a, const auto& b) {
        if (a.size() != b.size()) return false;
        for (std::size_t i = 0; i < a.size(); ++i)
            if (a[i].update != b[i].update || bits(a[i].event) != bits(b[i].event)) return false;
        return true;
    };
    EXPECT_TRUE(same(kept.car_touch_begins, expected.car_touch_begins));
    EXPECT_TRUE(same(kept.car_touch_ends, expected.car_touch_ends));
    EXPECT_TRUE(same(kept.body_hits, expected.body_hits));
    EXPECT_TRUE(kept.resets.empty());
    EXPECT_EQ(kept.car_touch_begins.front().event.car_b, 2u);

    const glm::dvec3 centre = runner.world().car(1).state().position;
    runner.world().car(1).apply_impulse({0.0, 1e300, 0.0}, centre + glm::dvec3(10.0, 0.0, 0.0));
    runner.run_to(kLast + 1);
    runner.wait();
    runner.take_events(kept);
    ASSERT_EQ(kept.resets.size(), 1u);
    EXPECT_EQ(kept.resets[0].update, kLast + 1);
    EXPECT_EQ(kept.resets[0].event.car, 2u);
    EXPECT_EQ(kept.resets[0].event.reason.rfind("before update 101: ", 0), 0u)
        << kept.resets[0].event.reason;

    PhysicsRunner quiet(three_cars(), false);
    quiet.run_to(kRemoved);
    quiet.wait();
    quiet.take_events(kept);
    EXPECT_TRUE(kept.empty());
}

// A runner made from a world that has run already says so at once (a game stamping inputs
// latest_update() + 2 stamps them after it), and a reset at update 6 while events are off is
// not reported once they are turned on later in the same run (in real time, at update 8).
TEST(PhysicsRunner, EventsAndTheLatestUpdateStartWhereTheWorldIs) {
    World world = three_cars();
    for (int u = 0; u < 5; ++u) world.update();
    PhysicsRunner runner(std::move(world), true);
    EXPECT_EQ(runner.latest_update(), 5u);
    const glm::dvec3 centre = runner.world().car(0).state().position;
    runner.world().car(0).apply_impulse({0.0, 1e300, 0.0}, centre + glm::dvec3(10.0, 0.0, 0.0));
    runner.start();
    while (runner.latest_update() < 8) std::this_thread::yield();
    runner.keep_events(true);
    while (runner.latest_update() < 12) std::this_thread::yield();
    runner.stop();
    ASSERT_EQ(runner.world().car_resets(0), 1u);
    RunnerEvents events;
    runner.take_events(events);
    EXPECT_TRUE(events.resets.empty()) << "stamped " << events.resets.front().update;
}

// A render thread reads the published poses of the cars that stay while the game removes one
// between runs (ThreadSanitizer: scripts/test_tsan.sh).
TEST(PhysicsRunner, RenderThreadReadsWhileACarIsRemoved) {
    PhysicsRunner runner(three_cars(), false);
    std::atomic<bool> done{false};
    std::atomic<int> reads{0};
    std::thread render([&] {
        while (!done.load()) {
            const double t = 0.01 * static_cast<double>(runner.published_update());
            for (const std::size_t car : {0u, 2u})
                if (!std::isfinite(runner.pose(car, t).position.x)) return;
            reads.fetch_add(1);
        }
    });
    runner.run_to(20);
    runner.wait();
    runner.remove_car(1);
    runner.run_to(40);
    runner.wait();
    done.store(true);
    render.join();
    EXPECT_GT(reads.load(), 0);
    EXPECT_EQ(runner.published_update(), 40u);
    EXPECT_THROW(runner.pose(1, 0.0), Error);
}

// Polls running() as a game that start()ed would, for at most 20 s.
void wait_until_it_stops(const PhysicsRunner& runner) {
    for (int ms = 0; ms < 20000 && runner.running(); ++ms)
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
}

// A run that reached its update leaves the world to the game without a wait(): the thread
// has ended, and the next run starts.
TEST(PhysicsRunner, TheWorldIsTheGamesOnceARunHasEnded) {
    PhysicsRunner runner(two_cars());
    runner.run_to(5);
    wait_until_it_stops(runner);
    EXPECT_FALSE(runner.running());
    EXPECT_EQ(runner.world().update_count(), 5u);
    runner.run_to(8);
    runner.wait();
    EXPECT_EQ(runner.world().update_count(), 8u);
}

// A job system that runs every range on worker 1 while it says it has one worker: each
// update throws on the physics thread.
void* on_a_worker_that_is_not_there(TaskCallback* task, int items, int, void* context, void*) {
    task(0, items, 1, context);
    return nullptr;
}

// An update that throws ends the run: running() says so, and the next call that needs the
// thread gone rethrows the error once (it used to say "the physics thread is running").
TEST(PhysicsRunner, AnUpdateThatThrowsEndsTheRunAndIsRethrownOnce) {
    WorldSettings settings;
    settings.jobs = {&on_a_worker_that_is_not_there, [](void*, void*) {}, nullptr, 1};
    PhysicsRunner runner(two_cars(CarSpec::default_car(), settings));
    runner.start();
    wait_until_it_stops(runner);
    EXPECT_FALSE(runner.running());
    const std::string why = test::error_of([&] { runner.world(); });
    EXPECT_NE(why.find("worker 1, outside 0 .. worker_count - 1 = 0"), std::string::npos) << why;
    EXPECT_NO_THROW(runner.world()) << "rethrown once";
    const std::string again = test::error_of([&] {
        runner.run_to(3);
        runner.wait();
    });
    EXPECT_NE(again.find("worker 1, outside"), std::string::npos) << again;
}

TEST(PhysicsRunner, StopEndsAnOpenRun) {
    PhysicsRunner runner(two_cars(), true);
    runner.start();
    EXPECT_THROW(runner.world(), Error);
    EXPECT_THROW(runner.start(), Error);
    runner.stop();
    EXPECT_NO_THROW(runner.world());
}

}  // namespace
}  // namespace trackphys
