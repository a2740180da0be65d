// The car's physics against analytic cases (docs/design.md#exactness-promises-and-their-tests):
// static sag, a bounce without damping, Coulomb's stopping distance, and contacts that never
// tunnel.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

#include "trackphys/error.hpp"
#include "trackphys/world/world.hpp"
#include "world/world_scenes.hpp"

namespace trackphys {
namespace {

// Body frame onto the world with the car facing +Z (identity) at height y.
RigidBodyState at_height(double y, const glm::dvec3& velocity = glm::dvec3(0.0)) {
    RigidBodyState state;
    state.position = {0.0, y, 0.0};
    state.linear_velocity = velocity;
    return state;
}

void run(World& world, double seconds) {
    const auto updates = static_cast<int>(std::lround(seconds / world.settings().dt_update));
    for (int i = 0; i < updates; ++i) world.update();
}

TEST(CarPhysics, SettlesToTheStaticSagAndStaysStill) {
    const CarSpec spec = CarSpec::default_car();
    World world(test::static_world_of(test::flat_grid(40.0, 80)));
    world.add_car(spec, at_height(0.52));
    run(world, 4.0);

    // Linear springs at rest carry the weight: the wheels' depths add up to m g / k.
    double total_depth = 0.0;
    int wheels = 0;
    for (std::size_t i = 0; i < spec.ellipsoids.size(); ++i) {
        if (spec.ellipsoids[i].role == EllipsoidRole::body) {
            EXPECT_LE(world.contacts(0)[i].depth, 0.0) << "body ellipsoid " << i << " touches";
            continue;
        }
        ++wheels;
        total_depth += world.contacts(0)[i].depth;
    }
    const double sag = spec.mass.mass * 9.81 / spec.wheel_contact.stiffness / wheels;
    EXPECT_NEAR(total_depth / wheels, sag, 0.01 * sag);
    // The suspension's springs carry it too: each wheel's travel holds its tyre's load.
    double total_travel = 0.0;
    for (const double travel : world.car(0).suspension()) total_travel += travel;
    const double spring_sag = spec.mass.mass * 9.81 / spec.suspension.stiffness / wheels;
    EXPECT_NEAR(total_travel / wheels, spring_sag, 0.01 * spring_sag);
    EXPECT_LT(glm::length(world.car(0).state().linear_velocity), 1e-3);

    // No creeping: two more seconds move it by less than 0.1 mm.
    const glm::dvec3 settled = world.car(0).state().position;
    run(world, 2.0);
    EXPECT_LT(glm::length(world.car(0).state().position - settled), 1e-4);
    EXPECT_LT(glm::length(world.car(0).state().linear_velocity), 1e-3);
}

// The sub-step's loops over wheels stop after the last wheel, and the presets list their
// wheels first: a car listing its body first, or a body ellipsoid between two wheels (which
// the loops over wheels must step over, not stop at), must drive as the preset does (to
// rounding, since its contacts' forces are summed in another order).
TEST(CarPhysics, ACarListingItsBodyFirstDrivesAsThePresetDoes) {
    const CarSpec preset = CarSpec::default_car();
    CarSpec body_first = preset;
    std::stable_partition(body_first.ellipsoids.begin(), body_first.ellipsoids.end(),
                          [](const CarEllipsoid& e) { return e.role == EllipsoidRole::body; });
    ASSERT_EQ(body_first.ellipsoids.front().role, EllipsoidRole::body);
    // The preset's four wheels, then its bodies: move the first body to the middle wheel.
    CarSpec body_between = preset;
    auto& between = body_between.ellipsoids;
    ASSERT_EQ(between[4].role, EllipsoidRole::body);
    std::rotate(between.begin() + 2, between.begin() + 4, between.begin() + 5);
    ASSERT_NE(between[1].role, EllipsoidRole::body);
    ASSERT_EQ(between[2].role, EllipsoidRole::body);
    ASSERT_NE(between[3].role, EllipsoidRole::body);
    const CarSpec* specs[] = {&preset, &body_first, &body_between};
    glm::dvec3 driven[3];
    for (int k = 0; k < 3; ++k) {
        World world(test::static_world_of(test::flat_grid(200.0, 100)));
        world.add_car(*specs[k], at_height(0.52));
        run(world, 1.0);
        world.car(0).set_inputs({0.6, 0.0, 0.3});
        run(world, 2.0);
        driven[k] = world.car(0).state().position;
    }
    EXPECT_GT(glm::length(driven[0]), 5.0);
    EXPECT_LT(glm::length(driven[1] - driven[0]), 1e-6);
    EXPECT_LT(glm::length(driven[2] - driven[0]), 1e-6);
}

// One stiff, undamped, frictionless ball dropped on the ground: a conservative spring,
// integrated symplectically, gives the energy back.
TEST(CarPhysics, UndampedBallBouncesBackToItsHeight) {
    CarSpec ball;
    ball.mass = {10.0, glm::dvec3(0.36)};
    ball.ellipsoids = {{{0.0, 0.0, 0.0}, glm::dvec3(0.3), {1, 0, 0, 0}, EllipsoidRole::body}};
    ball.body_contact = {1.0e6, 0.0, 0.0, 0.05};
    ball.drag_area = ball.downforce_area = 0.0;
    World world(test::static_world_of(test::flat_grid(10.0, 10)));
    const double drop = 1.0;  // the ball's bottom starts 1 m above the ground
    world.add_car(ball, at_height(0.3 + drop));

    double highest_after_bounce = -1.0;
    bool bounced = false;
    for (int i = 0; i < 150; ++i) {
        world.update();
        const RigidBodyState& s = world.car(0).state();
        if (s.linear_velocity.y > 0.0) bounced = true;
        if (bounced) highest_after_bounce = std::max(highest_after_bounce, s.position.y - 0.3);
    }
    ASSERT_TRUE(bounced);
    EXPECT_NEAR(highest_after_bounce, drop, 0.01 * drop);
}

// A sled (body ellipsoids only) sliding at 20 m/s stops after v^2 / (2 mu g).
TEST(CarPhysics, FrictionStopsASlidingCarWhereCoulombSays) {
    CarSpec sled;
    sled.mass = MassProperties::solid_box(800.0, {1.8, 0.6, 4.0});
    for (double x : {-0.7, 0.7})
        for (double z : {-1.5, 1.5})
            sled.ellipsoids.push_back(
                {{x, -0.2, z}, {0.2, 0.1, 0.4}, {1, 0, 0, 0}, EllipsoidRole::body});
    sled.body_contact = {4.0e5, 2.5e4, 0.5, 0.05};
    sled.drag_area = sled.downforce_area = 0.0;
    World world(test::static_world_of(test::flat_grid(120.0, 120)));
    const double speed = 20.0;
    world.add_car(sled, at_height(0.3 - 0.0049, {0.0, 0.0, speed}));  // resting on its skids

    const double start = world.car(0).state().position.z;
    for (int i = 0; i < 1000 && glm::length(world.car(0).state().linear_velocity) > 1e-3; ++i)
        world.update();
    const double expected = speed * speed / (2.0 * 0.5 * 9.81);
    EXPECT_NEAR(world.car(0).state().position.z - start, expected, 0.05 * expected);
}

TEST(CarPhysics, NoTunnellingIntoAWallAt1000KmH) {
    const double wall_z = 30.0;
    TriangleMesh scene = test::flat_grid(200.0, 100);
    const TriangleMesh barrier = test::wall(wall_z, 20.0, 3.0);
    const auto base = static_cast<std::uint32_t>(scene.vertices.size());
    scene.vertices.insert(scene.vertices.end(), barrier.vertices.begin(), barrier.vertices.end());
    for (auto t : barrier.triangles)
        scene.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});

    World world(test::static_world_of(scene));
    world.add_car(CarSpec::default_car(), at_height(0.52, {0.0, 0.0, 1000.0 / 3.6}));
    for (int i = 0; i < 100; ++i) {
        world.update();
        const Car& car = world.car(0);
        for (std::size_t e = 0; e < car.ellipsoid_count(); ++e)
            ASSERT_LT(car.world_ellipsoid(e).center().z, wall_z)
                << "ellipsoid " << e << " update " << i;
    }
    EXPECT_LT(world.car(0).state().linear_velocity.z, 1.0) << "the wall stopped the car";
}

TEST(CarPhysics, NoTunnellingThroughASingleTriangleRoadFrom100m) {
    TriangleMesh road;  // one big triangle, no thickness
    road.vertices = {{-50.0, 0.0, 50.0}, {50.0, 0.0, 50.0}, {0.0, 0.0, -80.0}};
    road.triangles = {{0, 1, 2}};
    World world(test::static_world_of(road));
    world.add_car(CarSpec::default_car(), at_height(100.0));
    for (int i = 0; i < 600; ++i) {
        world.update();
        const Car& car = world.car(0);
        for (std::size_t e = 0; e < car.ellipsoid_count(); ++e)
            ASSERT_GT(car.world_ellipsoid(e).center().y, 0.0)
                << "ellipsoid " << e << " update " << i;
    }
    EXPECT_LT(glm::length(world.car(0).state().linear_velocity), 0.5)
        << "it came to rest on the road";
}

// Sliding and driving straight across the seams of a finely triangulated flat road: the
// deepest contact is always a face contact, so no seam kicks the car up.
TEST(CarPhysics, NoGhostBumpsOnCoplanarSeams) {
    World world(test::static_world_of(test::straight_road(400.0, 12.0, 0.25)));
    RigidBodyState start = at_height(0.5 - 0.0147, {0.0, 0.0, 60.0});
    start.position.z = 10.0;
    world.add_car(CarSpec::default_car(), start);
    run(world, 0.5);  // settle the springs
    double worst = 0.0;
    for (int i = 0; i < 300; ++i) {
        world.car(0).set_inputs({0.3, 0.0, 0.0});
        world.update();
        worst = std::max(worst, std::abs(world.car(0).state().linear_velocity.y));
    }
    EXPECT_LT(worst, 0.01) << "vertical speed while crossing seams (m/s)";
}

TEST(CarPhysics, SameInputsGiveBitIdenticalStates) {
    const auto statics = test::static_world_of(test::flat_grid(100.0, 200));
    std::uint64_t hashes[2];
    for (std::uint64_t& hash : hashes) {
        World world(statics);
        world.add_car(CarSpec::default_car(), at_height(0.6));
        for (int i = 0; i < 200; ++i) {
            world.car(0).set_inputs({1.0, 0.0, std::sin(i * 0.05)});
            world.update();
        }
        hash = world.state_hash();
    }
    EXPECT_EQ(hashes[0], hashes[1]);
}

// A car's own state handed back (a lockstep peer adding the host's cars, a game reloading
// its own saved states) keeps every bit: set_state normalised the orientation again, which
// moved the last bit of some (4 of 20 mid-race states), and the worlds drove apart.
TEST(CarPhysics, ACarsOwnStateHandedBackKeepsItsBits) {
    const auto statics = test::static_world_of(test::flat_grid(100.0, 10));
    World driven(statics);
    driven.add_car(CarSpec::default_car(), at_height(0.6));
    World copy(statics);
    int changed = 0;
    for (int i = 0; i < 200; ++i) {
        driven.car(0).set_inputs({1.0, 0.0, std::sin(i * 0.05)});
        driven.update();
        const RigidBodyState own = driven.car(0).state();
        copy.add_car(CarSpec::default_car(), own);
        const glm::dquat q = copy.car(0).state().orientation;
        copy.remove_car(0);
        changed += std::memcmp(&q, &own.orientation, sizeof q) != 0;
        driven.car(0).set_state(own);
        const glm::dquat p = driven.car(0).state().orientation;
        changed += std::memcmp(&p, &own.orientation, sizeof p) != 0;
    }
    EXPECT_EQ(changed, 0);
    // Not a unit quaternion: normalised.
    RigidBodyState tilted = at_height(0.6);
    tilted.orientation = glm::dquat(2.0, 0.0, 0.0, 0.0);
    driven.car(0).set_state(tilted);
    EXPECT_EQ(driven.car(0).state().orientation, glm::dquat(1.0, 0.0, 0.0, 0.0));
}

TEST(CarPhysics, InvalidSettingsAndStatesAreRejected) {
    const auto statics = test::static_world_of(test::flat_grid(10.0, 2));
    WorldSettings bad;
    bad.dt_update = 0.0;
    EXPECT_THROW(World(statics, bad), Error);
    bad = WorldSettings{};
    bad.mid_phase_look_ahead = 0;
    EXPECT_THROW(World(statics, bad), Error);
    bad = WorldSettings{};
    bad.mid_phase_slack = -1.0;
    EXPECT_THROW(World(statics, bad), Error);
    EXPECT_THROW(World(nullptr), Error);
    World world(statics);
    RigidBodyState nan_state;
    nan_state.position.x = std::numeric_limits<double>::quiet_NaN();
    EXPECT_THROW(world.add_car(CarSpec::default_car(), nan_state), Error);
    CarSpec broken = CarSpec::default_car();
    broken.mass.mass = 0.0;
    EXPECT_THROW(world.add_car(broken, RigidBodyState{}), Error);
}

}  // namespace
}  // namespace trackphys
