// PhysicsRunner: stamped inputs replay bit-identically, the published pair of states
// interpolates between its ends, and a render thread reads it while the physics thread
// runs (these tests also run under ThreadSanitizer: scripts/test_tsan.sh).
#include "trackphys/world/physics_runner.hpp"

#include <atomic>
#include <cmath>
#include <cstdint>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "trackphys/error.hpp"
#include "trackphys/world/world.hpp"
#include "world/world_scenes.hpp"

namespace trackphys {
namespace {

// Two cars side by side on flat ground.
World two_cars() {
    World world(test::static_world_of(test::flat_grid(400.0, 40)));
    const CarSpec spec = CarSpec::default_car();
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
