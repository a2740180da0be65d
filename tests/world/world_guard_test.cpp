// The World's guards: the reset policy (a car in an impossible state is reset, never left to
// poison the world) and the API preconditions (settings, inputs, where a car is added).
#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <utility>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

#include "support/error_message.hpp"
#include "trackphys/error.hpp"
#include "trackphys/math/types.hpp"
#include "trackphys/world/spawn.hpp"
#include "trackphys/world/world.hpp"
#include "world/world_scenes.hpp"

namespace trackphys {
namespace {

using test::error_of;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

RigidBodyState at(const glm::dvec3& position, const glm::dvec3& velocity = glm::dvec3(0.0)) {
    RigidBodyState state;
    state.position = position;
    state.linear_velocity = velocity;
    return state;
}

bool finite(const RigidBodyState& s) {
    return is_finite(s.position) && is_finite(s.orientation) && is_finite(s.linear_velocity) &&
           is_finite(s.angular_velocity);
}

// An absurd but valid air density (1e300 kg/m^3) makes the drag at 5 m/s throw the car to
// ~1e294 m/s in one sub-step, and v . v overflows in the next: the state turns NaN
// mid-update. The car is reset to where the update began, at rest; from rest the drag is
// zero, the car falls, and the next update does it again. The world stays finite.
TEST(ResetPolicy, ANonFiniteCarIsResetToItsStartAtRest) {
    CarSpec absurd = CarSpec::default_car();
    absurd.air_density = 1e300;
    World world(test::static_world_of(test::flat_grid(40.0, 8)));
    const RigidBodyState start = at({0.0, 3.0, 0.0}, {0.0, 0.0, 5.0});
    world.add_car(absurd, start);
    world.car(0).set_inputs({0.7, 0.0, 0.1});
    for (int i = 1; i <= 5; ++i) {
        world.update();
        ASSERT_EQ(world.car_resets(0), static_cast<std::uint64_t>(i));
        const RigidBodyState& s = world.car(0).state();
        ASSERT_TRUE(finite(s));
        EXPECT_EQ(s.position, start.position);
        EXPECT_EQ(s.linear_velocity, glm::dvec3(0.0));
        EXPECT_EQ(s.angular_velocity, glm::dvec3(0.0));
        EXPECT_EQ(world.car(0).inputs().throttle, 0.7) << "inputs are kept";
        for (const Contact& c : world.contacts(0)) EXPECT_EQ(c.depth, -kInf);
    }
    EXPECT_NE(world.last_reset_reason(0).find("update 5: "), std::string::npos)
        << world.last_reset_reason(0);
    EXPECT_NE(world.last_reset_reason(0).find("not finite"), std::string::npos)
        << world.last_reset_reason(0);
}

// A strong gravity (300 g) pulls a car falling at 540 m/s past twice the design speed
// (555.6 m/s) in one update: reset once, then it falls from rest within the limits.
TEST(ResetPolicy, AnOverSpeedCarIsResetOnce) {
    WorldSettings strong;
    strong.gravity = {0.0, -3000.0, 0.0};
    World world(test::static_world_of(test::flat_grid(40.0, 8)), strong);
    const RigidBodyState start = at({0.0, 900.0, 0.0}, {0.0, -540.0, 0.0});
    world.add_car(CarSpec::default_car(), start);
    world.update();
    EXPECT_EQ(world.car_resets(0), 1u);
    EXPECT_EQ(world.car(0).state().position, start.position);
    EXPECT_NE(world.last_reset_reason(0).find("above WorldSettings.max_car_speed"),
              std::string::npos)
        << world.last_reset_reason(0);
    world.update();
    EXPECT_EQ(world.car_resets(0), 1u);
    EXPECT_GT(world.car(0).speed(), 20.0) << "falling again";
}

// A car dropped at 100 m/s onto its corner (rolled 60 degrees) spins up in the impact; with
// the limit at 5 rad/s that is an impossible state.
TEST(ResetPolicy, AnOverSpinningCarIsReset) {
    WorldSettings tight;
    tight.max_car_angular_speed = 5.0;
    World world(test::static_world_of(test::flat_grid(40.0, 8)), tight);
    RigidBodyState start = at({0.0, 2.0, 0.0}, {0.0, -100.0, 0.0});
    start.orientation = glm::angleAxis(1.05, glm::dvec3(0.0, 0.0, 1.0));
    world.add_car(CarSpec::default_car(), start);
    for (int i = 0; i < 10 && world.car_resets(0) == 0; ++i) world.update();
    EXPECT_GE(world.car_resets(0), 1u);
    EXPECT_NE(world.last_reset_reason(0).find("angular speed"), std::string::npos)
        << world.last_reset_reason(0);
    EXPECT_LE(glm::length(world.car(0).state().angular_velocity), 5.0);
}

TEST(ResetPolicy, ResetsTravelWithSnapshots) {
    WorldSettings strong;
    strong.gravity = {0.0, -3000.0, 0.0};
    World world(test::static_world_of(test::flat_grid(40.0, 8)), strong);
    world.add_car(CarSpec::default_car(), at({0.0, 900.0, 0.0}, {0.0, -540.0, 0.0}));
    world.update();
    World copy(test::static_world_of(test::flat_grid(40.0, 8)), strong);
    copy.add_car(CarSpec::default_car(), at({0.0, 900.0, 0.0}));
    copy.restore_state(world.save_state());
    EXPECT_EQ(copy.car_resets(0), 1u);
}

// A push a game gives between updates: a non-finite one is refused at once and changes
// nothing; a finite one that spins the car far beyond the limits (an impulse of 1e300 N s
// 10 m from its centre) leaves a car the next update resets at rest where it is, before its
// broad phase, whose box it would make infinite for every car. The other car drives on as
// in a world without the push, and the pushed one drives on after its reset.
TEST(ResetPolicy, ACarPushedBeyondTheLimitsBetweenUpdatesIsResetBeforeTheUpdate) {
    const auto two_cars = [] {
        auto world = std::make_unique<World>(test::static_world_of(test::flat_grid(80.0, 16)));
        for (const double x : {-10.0, 10.0})
            world->add_car(CarSpec::default_car(), at({x, 0.6, 0.0}));
        for (int i = 0; i < 2; ++i) world->car(i).set_inputs({0.5, 0.0, 0.0});
        world->update();
        return world;
    };
    const std::unique_ptr<World> pushed = two_cars(), untouched = two_cars();
    Car& car = pushed->car(0);
    const RigidBodyState before = car.state();
    for (const auto& [impulse, point] :
         {std::pair{glm::dvec3(0.0, kNaN, 0.0), before.position},
          std::pair{glm::dvec3(0.0, 1.0, 0.0), glm::dvec3(kInf, 0.0, 0.0)},
          std::pair{glm::dvec3(0.0, 1e308, 0.0), before.position + glm::dvec3(1e10, 0.0, 0.0)}}) {
        EXPECT_NE(error_of([&] {
                      car.apply_impulse(impulse, point);
                  }).find("Car::apply_impulse: impulse ("),
                  std::string::npos);
        EXPECT_EQ(car.state().angular_velocity, before.angular_velocity) << "unchanged";
    }
    car.apply_impulse({0.0, 1e300, 0.0}, before.position + glm::dvec3(10.0, 0.0, 0.0));
    ASSERT_TRUE(finite(car.state()));
    pushed->update();
    untouched->update();
    EXPECT_EQ(pushed->car_resets(0), 1u);
    const std::string why = pushed->last_reset_reason(0);
    EXPECT_EQ(why.rfind("before update 2: ", 0), 0u) << why;
    EXPECT_NE(why.find("above WorldSettings.max_car_"), std::string::npos) << why;
    EXPECT_EQ(why.find("inf"), std::string::npos) << "a speed whose square overflows: " << why;
    // Reset at rest where it was, then one update from there: it has barely moved.
    EXPECT_LT(glm::distance(pushed->car(0).state().position, before.position), 0.01);
    EXPECT_LT(pushed->car(0).speed(), 0.5);
    EXPECT_EQ(pushed->car_resets(1), 0u);
    EXPECT_EQ(pushed->car(1).state().position, untouched->car(1).state().position);
    for (int i = 0; i < 20; ++i) pushed->update();
    EXPECT_EQ(pushed->car_resets(0), 1u);
    EXPECT_GT(glm::distance(pushed->car(0).state().position, before.position), 0.02)
        << "it drives on";
}

TEST(Preconditions, WorldSettingsNameTheFieldAndTheReason) {
    const auto statics = test::static_world_of(test::flat_grid(10.0, 2));
    const auto message = [&](auto change) {
        WorldSettings settings;
        change(settings);
        return error_of([&] { World world(statics, settings); });
    };
    for (const double dt : {0.0, -0.01, kNaN, kInf})
        EXPECT_NE(message([dt](WorldSettings& s) {
                      s.dt_update = dt;
                  }).find("WorldSettings.dt_update must be in (0, 1]"),
                  std::string::npos)
            << dt;
    EXPECT_NE(message([](WorldSettings& s) { s.steps = 0; }).find("WorldSettings.steps"),
              std::string::npos);
    EXPECT_NE(message([](WorldSettings& s) { s.substeps = -1; }).find("WorldSettings.substeps"),
              std::string::npos);
    EXPECT_NE(message([](WorldSettings& s) { s.gravity.y = kNaN; }).find("WorldSettings.gravity"),
              std::string::npos);
    EXPECT_NE(message([](WorldSettings& s) {
                  s.gravity.y = -1e300;
              }).find("WorldSettings.gravity must be finite and at most"),
              std::string::npos);
    EXPECT_NE(message([](WorldSettings& s) {
                  s.max_car_speed = 0.0;
              }).find("WorldSettings.max_car_speed"),
              std::string::npos);
    EXPECT_NE(message([](WorldSettings& s) {
                  s.max_car_angular_speed = kNaN;
              }).find("WorldSettings.max_car_angular_speed"),
              std::string::npos);
    EXPECT_NE(message([](WorldSettings& s) {
                  s.max_spawn_distance = -1.0;
              }).find("WorldSettings.max_spawn_distance"),
              std::string::npos);
}

// Plane trees handed to a World must be its colliders': another world's, fewer or a null
// one are refused when the World is made, not at the first add_car or update (or never,
// when another map's trees of the same count filtered the wrong triangles).
TEST(Preconditions, PlaneTreesOfAnotherStaticWorldAreRefused) {
    const auto statics = test::static_world_of(test::flat_grid(10.0, 2));  // 8 triangles
    const auto other = test::static_world_of(test::flat_grid(10.0, 3));    // 18
    const World own(statics);
    EXPECT_NO_THROW(World(statics, {}, own.plane_trees()));
    EXPECT_EQ(error_of([&] { World(statics, {}, World(other).plane_trees()); }),
              "World: plane tree 0 holds 18 triangles, collider 0 8: the trees are not this "
              "static world's");
    ColliderPlaneTrees two = own.plane_trees();
    two.push_back(two[0]);
    EXPECT_EQ(error_of([&] { World(statics, {}, two); }),
              "World: 2 plane trees for 1 colliders: the trees are not this static world's");
    ColliderPlaneTrees null_tree(1);
    EXPECT_EQ(error_of([&] { World(statics, {}, null_tree); }), "World: plane tree 0 is null");
}

TEST(Preconditions, NaNInputsAreRejectedAndInfinitiesClamped) {
    Car car(CarSpec::default_car(), RigidBodyState{});
    car.set_inputs({0.5, 0.25, -0.5});
    EXPECT_NE(error_of([&] {
                  car.set_inputs({kNaN, 0.0, 0.0});
              }).find("throttle is NaN"),
              std::string::npos);
    EXPECT_NE(error_of([&] {
                  car.set_inputs({0.0, kNaN, 0.0});
              }).find("brake is NaN"),
              std::string::npos);
    EXPECT_NE(error_of([&] {
                  car.set_inputs({0.0, 0.0, kNaN});
              }).find("steer is NaN"),
              std::string::npos);
    EXPECT_EQ(car.inputs().throttle, 0.5) << "a rejected input changes nothing";
    car.set_inputs({kInf, -kInf, kInf});
    EXPECT_EQ(car.inputs().throttle, 1.0);
    EXPECT_EQ(car.inputs().brake, 0.0);
    EXPECT_EQ(car.inputs().steer, 1.0);
    // A negative throttle asks for reverse: kept down to -1, clamped beyond.
    car.set_inputs({-0.4, 0.0, 0.0});
    EXPECT_EQ(car.inputs().throttle, -0.4);
    car.set_inputs({-kInf, 0.0, 0.0});
    EXPECT_EQ(car.inputs().throttle, -1.0);
}

TEST(Preconditions, ACarInsideGeometryIsRejected) {
    TriangleMesh scene = test::flat_grid(40.0, 8);
    const TriangleMesh barrier = test::wall(5.0, 10.0, 3.0);
    const auto base = static_cast<std::uint32_t>(scene.vertices.size());
    scene.vertices.insert(scene.vertices.end(), barrier.vertices.begin(), barrier.vertices.end());
    for (auto t : barrier.triangles)
        scene.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
    World world(test::static_world_of(scene));

    // Wheels 20 cm into the ground (more than half of their 15 cm half-width).
    const std::string sunk = error_of([&] {
        world.add_car(CarSpec::default_car(), at({0.0, 0.3, 0.0}));
    });
    EXPECT_NE(sunk.find("inside geometry"), std::string::npos) << sunk;
    EXPECT_NE(sunk.find("wheel"), std::string::npos) << sunk;
    // Through the wall.
    const std::string walled = error_of([&] {
        world.add_car(CarSpec::default_car(), at({0.0, 0.52, 5.0}));
    });
    EXPECT_NE(walled.find("inside geometry"), std::string::npos) << walled;
    EXPECT_EQ(world.car_count(), 0u);
    // Resting on the ground with its wheels 1 cm deep, or a millimetre above it: fine.
    EXPECT_NO_THROW(world.add_car(CarSpec::default_car(), at({0.0, 0.49, -5.0})));
    EXPECT_NO_THROW(world.add_car(CarSpec::default_car(), at({0.0, 0.501, -10.0})));
}

TEST(Preconditions, ACarFarOutsideTheMapIsRejected) {
    World world(test::static_world_of(test::flat_grid(40.0, 8)));
    const std::string far = error_of([&] {
        world.add_car(CarSpec::default_car(), at({5000.0, 1.0, 0.0}));
    });
    EXPECT_NE(far.find("far outside the map"), std::string::npos) << far;
    EXPECT_NE(far.find("WorldSettings.max_spawn_distance"), std::string::npos) << far;
    EXPECT_NO_THROW(world.add_car(CarSpec::default_car(), at({0.0, 900.0, 0.0})));
    EXPECT_NO_THROW(world.add_car(CarSpec::default_car(), at({1000.0, 5.0, 0.0})));

    // A world without triangles has no map: anywhere goes.
    World empty(std::make_shared<StaticWorld>());
    EXPECT_NO_THROW(empty.add_car(CarSpec::default_car(), at({1e6, 0.0, 0.0})));
}

TEST(Preconditions, ATeleportIsCheckedAsAnAddedCarIs) {
    World world(test::static_world_of(test::flat_grid(40.0, 8)));
    const std::size_t car = world.add_car(CarSpec::default_car(), at({0.0, 0.501, 0.0}));
    for (const auto& [state, reason] :
         {std::pair{at({0.0, 0.2, 0.0}), "inside geometry"},
          std::pair{at({5000.0, 1.0, 0.0}), "far outside the map"},
          std::pair{at({0.0, 1.0, 0.0}, {1e4, 0.0, 0.0}), "WorldSettings.max_car_speed"}}) {
        const std::string why = error_of([&] { world.teleport_car(car, state); });
        EXPECT_NE(why.find(std::string("World::teleport_car: ")), std::string::npos) << why;
        EXPECT_NE(why.find(reason), std::string::npos) << why;
        EXPECT_EQ(world.car(car).state().position, glm::dvec3(0.0, 0.501, 0.0))
            << "a refused teleport leaves the car where it was";
    }
    world.teleport_car(car, at({10.0, 0.501, -10.0}, {0.0, 0.0, 20.0}));
    EXPECT_EQ(world.car(car).state().position, glm::dvec3(10.0, 0.501, -10.0));
    EXPECT_EQ(world.car(car).state().linear_velocity, glm::dvec3(0.0, 0.0, 20.0));
}

// A teleport hangs the wheels at full droop, as add_car does: the default car squatting under
// full throttle (rear suspension ~7 cm compressed) is refused its own state, its rear wheel
// ~8 cm into the road there, and the error says why and what to use instead.
TEST(Preconditions, ATeleportHangsTheWheelsAtFullDroop) {
    World world(test::static_world_of(test::flat_grid(200.0, 8)));
    world.add_car(CarSpec::default_car(), at({0.0, 0.501, 0.0}));
    world.car(0).set_inputs({1.0, 0.0, 0.0});
    for (int i = 0; i < 100; ++i) world.update();
    const RigidBodyState squatting = world.car(0).state();
    EXPECT_GT(world.car(0).suspension(1), 0.05) << "rear wheel";

    const std::string why = error_of([&] { world.teleport_car(0, squatting); });
    EXPECT_NE(why.find("(rear wheel) is 0.07"), std::string::npos) << why;
    EXPECT_NE(why.find("full droop: place_car_on_surface gives the height"), std::string::npos)
        << why;
    EXPECT_EQ(world.car(0).state().position, squatting.position);

    const RigidBodyState resting = place_car_on_surface(world.statics(), world.car(0).spec(),
                                                        squatting.position, squatting.orientation);
    world.teleport_car(0, resting);
    EXPECT_EQ(world.car(0).suspension(1), 0.0);
    EXPECT_GT(world.car(0).state().position.y, squatting.position.y);
}

TEST(Preconditions, ACarIndexPastTheLastCarIsAnErrorNamingBoth) {
    World world(std::make_shared<StaticWorld>());
    world.add_car(CarSpec::default_car(), at({0.0, 5.0, 0.0}));
    const World& read_only = world;
    for (const std::string& why :
         {error_of([&] { world.car(1); }), error_of([&] { read_only.car(1); }),
          error_of([&] { world.contacts(1); }), error_of([&] { world.car_resets(1); }),
          error_of([&] { world.last_reset_reason(1); })})
        EXPECT_NE(why.find("no car 1: the world has 1 car"), std::string::npos) << why;
    EXPECT_NO_THROW(world.car(0));
}

// Before its first update an added car has touched nothing, written as after a reset: a
// game testing depth >= 0 sees no touch.
TEST(Preconditions, AnAddedCarHasNoContactsUntilItsFirstUpdate) {
    World world(test::static_world_of(test::flat_grid(40.0, 8)));
    world.add_car(CarSpec::default_car(), at({0.0, 5.0, 0.0}));
    for (const Contact& c : world.contacts(0)) {
        EXPECT_EQ(c.depth, -kInf);
        EXPECT_EQ(c.normal, glm::dvec3(0.0));
    }
}

TEST(Preconditions, AnEllipsoidIndexPastTheCarsIsAnErrorNamingBoth) {
    World world(std::make_shared<StaticWorld>());
    world.add_car(CarSpec::default_car(), at({0.0, 5.0, 0.0}));
    const Car& car = world.car(0);
    const std::size_t past = car.ellipsoid_count();
    const std::string expected = "the car has no ellipsoid " + std::to_string(past) + " (it has " +
                                 std::to_string(past) + ")";
    EXPECT_EQ(error_of([&] { car.suspension(past); }), expected);
    EXPECT_EQ(error_of([&] { car.body_ellipsoid(past); }), expected);
    EXPECT_EQ(error_of([&] { car.world_ellipsoid(past); }), expected);
    EXPECT_NO_THROW(car.world_ellipsoid(past - 1));
}

TEST(Preconditions, ImpossibleStartsAreRejected) {
    World world(test::static_world_of(test::flat_grid(40.0, 8)));
    EXPECT_NE(error_of([&] {
                  world.add_car(CarSpec::default_car(), at({0.0, 5.0, 0.0}, {600.0, 0.0, 0.0}));
              }).find("above WorldSettings.max_car_speed"),
              std::string::npos);
    RigidBodyState spinning = at({0.0, 5.0, 0.0});
    spinning.angular_velocity = {0.0, 600.0, 0.0};
    EXPECT_NE(
        error_of([&] { world.add_car(CarSpec::default_car(), spinning); }).find("angular speed"),
        std::string::npos);
}

// One ellipsoid on a point mass of 1 kg: the bound h^2 k / m <= 4 at the centre of mass,
// and half the mass where the turning term 2 / I (at 1 m along z, I = 2) adds as much.
CarSpec one_ball_car(const glm::dvec3& center, double stiffness) {
    CarSpec spec = CarSpec::default_car();
    spec.mass.mass = 1.0;
    spec.mass.principal_inertia = glm::dvec3(2.0);
    spec.ellipsoids = {{center, glm::dvec3(0.2), {1, 0, 0, 0}, EllipsoidRole::body}};
    spec.body_contact = {stiffness, 0.0, 0.5, 0.05};
    return spec;
}

TEST(Preconditions, ContactsTooStiffForTheSubStepAreRejected) {
    const auto ground = test::static_world_of(test::flat_grid(40.0, 8));
    const double h = World(ground).settings().substep_dt();
    // Each car alone in its world: two would meet the test of the spring between cars.
    const auto add_alone = [&](const CarSpec& spec) {
        World(ground).add_car(spec, at({0.0, 5.0, 0.0}));
    };
    const double limit = 4.0 / (h * h);  // N/m on 1 kg
    EXPECT_NO_THROW(add_alone(one_ball_car({0, 0, 0}, limit)));
    const std::string stiff = error_of([&] {
        add_alone(one_ball_car({0, 0, 0}, limit * (1.0 + 0x1p-40)));
    });
    EXPECT_NE(stiff.find("CarSpec.body_contact"), std::string::npos) << stiff;
    EXPECT_NE(stiff.find("too stiff for a sub-step"), std::string::npos) << stiff;
    EXPECT_NO_THROW(add_alone(one_ball_car({0, 0, 1}, limit / 2)));
    EXPECT_NE(error_of([&] {
                  add_alone(one_ball_car({0, 0, 1}, limit / 2 * (1.0 + 0x1p-40)));
              }).find("effective mass may be as low as 0.5 kg"),
              std::string::npos);

    // Damping counts too: 2 h c / m alone at 4.
    CarSpec damped = one_ball_car({0, 0, 0}, 1.0);
    damped.body_contact.damping = 2.0 / h;
    EXPECT_NE(error_of([&] { add_alone(damped); }).find("damping"), std::string::npos);

    // What a unit slip or an exploded car spec looks like: refused, naming the material.
    CarSpec feather = CarSpec::default_car();
    feather.mass.principal_inertia = glm::dvec3(1e-9);
    EXPECT_NE(error_of([&] { add_alone(feather); }).find("CarSpec."), std::string::npos);
    CarSpec hard = CarSpec::default_car();
    hard.wheel_contact.stiffness = 1e30;
    EXPECT_NE(error_of([&] { add_alone(hard); }).find("CarSpec.wheel_contact"), std::string::npos);
    // Every preset drives.
    for (std::string_view name : CarSpec::preset_names())
        EXPECT_NO_THROW(add_alone(CarSpec::preset(name))) << name;
}

// A vehicle's wheel spin, explicit against its tyre's force above low_speed, is stable while
// h^2 R^2 C / (I sigma) < 4 + 2 h low_speed / sigma, C = B C D at ten nominal loads, its
// friction coefficient held from three (physreview: the gt's tyre force swung over its full
// +-D at 8.33 ms sub-steps; a review: a wheel checked at three loads swung at four).
TEST(Preconditions, AWheelSpinTooStiffForTheSubStepIsRejected) {
    const CarSpec gt = CarSpec::preset("gt");
    World fine(test::static_world_of(test::flat_grid(40.0, 8)));
    EXPECT_NO_THROW(fine.add_car(gt, at({0.0, 5.0, 0.0})));

    WorldSettings coarse;  // 8.33 ms sub-steps: 60 updates a second, 2 steps of 1 sub-step
    coarse.dt_update = 1.0 / 60.0;
    coarse.steps = 2;
    coarse.substeps = 1;
    World world(test::static_world_of(test::flat_grid(40.0, 8)), coarse);
    const std::string why = error_of([&] { world.add_car(gt, at({0.0, 5.0, 0.0})); });
    EXPECT_NE(why.find("_tyre's wheel spin is too stiff for a sub-step of 0.00833"),
              std::string::npos)
        << why;

    // At the bound, from the formula for the grippier rear tyre: a wheel a hair lighter is
    // refused, one a hair heavier taken.
    const double h = fine.settings().substep_dt();
    const TyreSpec& tyre = gt.vehicle->rear_tyre;
    const double load = 10.0 * tyre.nominal_load;
    const double slope = tyre.longitudinal.stiffness * tyre.longitudinal.shape *
                         tyre.longitudinal.friction *
                         (1.0 + 2.0 * tyre.longitudinal.friction_load_slope) * load;
    const double sigma = tyre.longitudinal_relaxation;
    const double r = 0.35;
    const double inertia =
        h * h * r * r * slope / (sigma * (4.0 + 2.0 * h * gt.vehicle->low_speed / sigma));
    CarSpec light = gt;
    light.vehicle->wheel_inertia = inertia * (1.0 - 1e-9);
    EXPECT_NE(error_of([&] {
                  fine.add_car(light, at({0.0, 5.0, 10.0}));
              }).find("rear_tyre's wheel spin"),
              std::string::npos);
    light.vehicle->wheel_inertia = inertia * (1.0 + 1e-9);
    EXPECT_NO_THROW(fine.add_car(light, at({0.0, 5.0, 10.0})));
}

// The suspension's travel is explicit: stable while h (k + k_t + 2 a) / c < 2 (k_t the
// tyre's contact stiffness, a the axle's anti-roll rate). Beyond it the travel swings
// between its stops at every sub-step (a review: a damping of 1 N s/m cost the default car a
// quarter of its top speed).
TEST(Preconditions, ASuspensionTooStiffForTheSubStepIsRejected) {
    World world(test::static_world_of(test::flat_grid(40.0, 8)));
    const double h = world.settings().substep_dt();
    CarSpec car = CarSpec::default_car();
    const double springs = car.suspension.stiffness + car.wheel_contact.stiffness;
    car.suspension.damping = h * springs / 2.0 * (1.0 - 1e-9);
    EXPECT_NE(error_of([&] {
                  world.add_car(car, at({0.0, 5.0, 0.0}));
              }).find("CarSpec.suspension.damping 57.5 N s/m is too low"),
              std::string::npos);
    car.suspension.damping = h * springs / 2.0 * (1.0 + 1e-9);
    EXPECT_NO_THROW(world.add_car(car, at({0.0, 5.0, 0.0})));

    // The anti-roll bar stiffens the mode where an axle's wheels move against each other.
    CarSpec gt = CarSpec::preset("gt");
    const double c = gt.suspension.damping;
    const double gt_springs = gt.suspension.stiffness + gt.wheel_contact.stiffness;
    gt.vehicle->rear_anti_roll = (2.0 * c / h - gt_springs) / 2.0 * (1.0 + 1e-9);
    const std::string why = error_of([&] { world.add_car(gt, at({0.0, 5.0, 10.0})); });
    EXPECT_NE(why.find("+ 2 vehicle.rear_anti_roll"), std::string::npos) << why;
    EXPECT_NE(why.find(") / damping is 2"), std::string::npos) << why;
    gt.vehicle->rear_anti_roll = (2.0 * c / h - gt_springs) / 2.0 * (1.0 - 1e-9);
    EXPECT_NO_THROW(world.add_car(gt, at({0.0, 5.0, 10.0})));
}

}  // namespace
}  // namespace trackphys
