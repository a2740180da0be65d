// Contacts between cars (docs/design.md#cars-between-cars): what a collision conserves, what
// it loses, that it never lets cars through each other, and that a stack of cars rests.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <numbers>
#include <random>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/mat3x3.hpp>

#include "support/error_message.hpp"
#include "trackphys/geometry/ellipsoid_pair.hpp"
#include "trackphys/world/world.hpp"
#include "world/car_pair_contact.hpp"
#include "world/world_scenes.hpp"

namespace trackphys {
namespace {

// No drag, no downforce: in free space only the cars' contact acts on them.
CarSpec free_space_car() {
    CarSpec spec = CarSpec::default_car();
    spec.air_density = 0.0;
    return spec;
}

WorldSettings without_gravity() {
    WorldSettings settings;
    settings.gravity = glm::dvec3(0.0);
    return settings;
}

RigidBodyState moving(const glm::dvec3& position, double heading, const glm::dvec3& velocity,
                      const glm::dvec3& spin = glm::dvec3(0.0)) {
    RigidBodyState state;
    state.position = position;
    state.orientation = glm::angleAxis(heading, glm::dvec3(0.0, 1.0, 0.0));
    state.linear_velocity = velocity;
    state.angular_velocity = spin;
    return state;
}

glm::dvec3 momentum(const World& world) {
    glm::dvec3 sum(0.0);
    for (std::size_t i = 0; i < world.car_count(); ++i)
        sum += world.car(i).spec().mass.mass * world.car(i).state().linear_velocity;
    return sum;
}

// About the origin: x x m v plus the spin I_world omega of each car.
glm::dvec3 angular_momentum(const World& world) {
    glm::dvec3 sum(0.0);
    for (std::size_t i = 0; i < world.car_count(); ++i) {
        const RigidBodyState& s = world.car(i).state();
        const MassProperties& mass = world.car(i).spec().mass;
        const glm::dvec3 body_spin = glm::conjugate(s.orientation) * s.angular_velocity;
        sum += glm::cross(s.position, mass.mass * s.linear_velocity) +
               s.orientation * (mass.principal_inertia * body_spin);
    }
    return sum;
}

double kinetic_energy(const World& world) {
    double sum = 0.0;
    for (std::size_t i = 0; i < world.car_count(); ++i)
        sum += kinetic_energy(world.car(i).state(), world.car(i).spec().mass);
    return sum;
}

// Runs updates until the cars have touched and come apart again; returns the updates with a
// contact between them.
int collide(World& world) {
    int touching = 0;
    for (int update = 0; update < 400; ++update) {
        world.update();
        if (world.last_profile().car_contacts > 0)
            ++touching;
        else if (touching > 0)
            return touching;
    }
    return touching;
}

// A car of one ellipsoid centred on its centre of mass, for collisions in a plane: at
// equal heights the contacts push horizontally at the centres' height, so the cars spin
// about their vertical principal axes only and the integrator's gyroscopic term is zero
// (a spin about a tilted axis drifts the angular momentum under explicit Euler,
// independently of contacts).
CarSpec puck_car() {
    CarSpec spec = free_space_car();
    spec.ellipsoids = {{glm::dvec3(0.0), {1.0, 0.5, 2.2}, {1, 0, 0, 0}, EllipsoidRole::body}};
    return spec;
}

// Two cars meeting at an angle, off centre, one of them spinning: the contact forces are
// equal and opposite at the same point, so the totals do not move beyond rounding.
TEST(CarContact, ConservesLinearAndAngularMomentum) {
    World world(std::make_shared<StaticWorld>(), without_gravity());
    const CarSpec spec = puck_car();
    world.add_car(spec, moving({0.0, 0.0, 0.0}, 0.0, {0.0, 0.0, 9.0}));
    world.add_car(spec, moving({1.5, 0.0, 7.0}, 0.6, {-2.0, 0.0, -5.0}, {0.0, 0.3, 0.0}));
    const glm::dvec3 p0 = momentum(world);
    const glm::dvec3 l0 = angular_momentum(world);

    ASSERT_GT(collide(world), 0) << "the cars never touched";
    EXPECT_LE(glm::length(momentum(world) - p0), 1e-9 * glm::length(p0));
    EXPECT_LE(glm::length(angular_momentum(world) - l0), 1e-9 * glm::length(l0));
    // The collision did something: the first car's velocity and spin changed.
    EXPECT_GT(glm::length(world.car(0).state().linear_velocity - glm::dvec3(0.0, 0.0, 9.0)), 0.5);
    EXPECT_GT(glm::length(world.car(0).state().angular_velocity), 0.1);
}

// The same for the default cars in three dimensions, over one sub-step of their contact:
// every push is an equal and opposite impulse at one point.
TEST(CarContact, EachSubStepConservesMomentumOfTheDefaultCars) {
    const CarSpec spec = free_space_car();
    Car a(spec, moving({0.0, 0.0, 0.0}, 0.0, {0.0, 0.0, 30.0}, {0.2, 0.1, 0.0}));
    Car b(spec, moving({1.0, 0.2, 3.4}, 0.6, {-8.0, 0.5, -20.0}, {0.0, 0.3, 0.1}));
    std::vector<Ellipsoid> a_placed;
    std::vector<Ellipsoid> b_placed;
    for (std::size_t i = 0; i < a.ellipsoid_count(); ++i) a_placed.push_back(a.world_ellipsoid(i));
    for (std::size_t i = 0; i < b.ellipsoid_count(); ++i) b_placed.push_back(b.world_ellipsoid(i));
    const auto totals = [&] {
        const double m = spec.mass.mass;
        const auto spin = [&](const Car& car) {
            const RigidBodyState& s = car.state();
            return s.orientation * (spec.mass.principal_inertia *
                                    (glm::conjugate(s.orientation) * s.angular_velocity));
        };
        const RigidBodyState& sa = a.state();
        const RigidBodyState& sb = b.state();
        return std::pair{m * (sa.linear_velocity + sb.linear_velocity),
                         glm::cross(sa.position, m * sa.linear_velocity) +
                             glm::cross(sb.position, m * sb.linear_velocity) + spin(a) + spin(b)};
    };
    const auto [p0, l0] = totals();

    const detail::CarPairTouch touch = detail::touch_cars(a, a_placed, b, b_placed, 2.5e-4);
    ASSERT_GT(touch.deepest, 0.0) << "the cars do not overlap";
    const auto [p1, l1] = totals();
    EXPECT_LE(glm::length(p1 - p0), 1e-9 * glm::length(p0));
    EXPECT_LE(glm::length(l1 - l0), 1e-9 * glm::length(l0));
    EXPECT_GT(glm::length(a.state().linear_velocity - glm::dvec3(0.0, 0.0, 30.0)), 0.1);
}

// touch_cars first keeps each car's ellipsoids that reach into the other car's sphere: it
// must leave out only pairs that ellipsoids_may_touch rejects too. Default cars in reach of
// each other, nose to tail, side by side and tilted, against every pair of the two.
TEST(CarContact, TestsEveryEllipsoidPairTheCullsLetThrough) {
    const CarSpec spec = free_space_car();
    std::mt19937 random(16);
    std::uniform_real_distribution<double> offset(-4.0, 4.0);
    std::uniform_real_distribution<double> angle(-std::numbers::pi, std::numbers::pi);
    std::uniform_real_distribution<double> tilt(-0.6, 0.6);
    int row_left_out = 0;
    for (int trial = 0; trial < 2000; ++trial) {
        RigidBodyState state_b = moving({offset(random), 0.3 * offset(random), offset(random)},
                                        angle(random), glm::dvec3(0.0));
        state_b.orientation =
            glm::angleAxis(tilt(random), glm::dvec3(1.0, 0.0, 0.0)) * state_b.orientation;
        Car a(spec, moving(glm::dvec3(0.0), 0.0, glm::dvec3(0.0)));
        Car b(spec, state_b);
        std::vector<Ellipsoid> a_placed;
        std::vector<Ellipsoid> b_placed;
        for (std::size_t i = 0; i < a.ellipsoid_count(); ++i)
            a_placed.push_back(a.world_ellipsoid(i));
        for (std::size_t i = 0; i < b.ellipsoid_count(); ++i)
            b_placed.push_back(b.world_ellipsoid(i));
        std::uint64_t passing = 0;
        bool some_row_empty = false;  // an ellipsoid of a that meets none of b's
        for (const Ellipsoid& ea : a_placed) {
            std::uint64_t in_row = 0;
            for (const Ellipsoid& eb : b_placed) in_row += ellipsoids_may_touch(ea, eb);
            passing += in_row;
            some_row_empty = some_row_empty || in_row == 0;
        }
        const detail::CarPairTouch touch = detail::touch_cars(a, a_placed, b, b_placed, 2.5e-4);
        ASSERT_EQ(touch.exact_tests, passing) << "trial " << trial;
        // The car-sphere test drops whole ellipsoids: the trials that matter have an
        // ellipsoid near the other car that meets none of its ellipsoids, beside some that do.
        row_left_out += passing > 0 && some_row_empty;
    }
    EXPECT_GT(row_left_out, 100) << "too few cases where an ellipsoid near the other car "
                                    "meets none of its ellipsoids";
}

// Without damping and friction the contact is a conservative spring.
TEST(CarContact, LosesNoEnergyWithoutDampingOrFriction) {
    World world(std::make_shared<StaticWorld>(), without_gravity());
    CarSpec spec = free_space_car();
    spec.car_contact.damping = 0.0;
    spec.car_contact.friction = 0.0;
    world.add_car(spec, moving({0.0, 0.0, 0.0}, 0.0, {0.0, 0.0, 6.0}));
    world.add_car(spec, moving({1.0, 0.2, 7.0}, 0.5, {-1.5, 0.0, -4.0}));
    const double before = kinetic_energy(world);

    ASSERT_GT(collide(world), 0) << "the cars never touched";
    EXPECT_NEAR(kinetic_energy(world), before, 0.01 * before);
    EXPECT_GT(glm::length(world.car(0).state().linear_velocity - glm::dvec3(0.0, 0.0, 6.0)), 0.5);
}

// With damping and friction the same collision loses energy, and never gains any.
TEST(CarContact, DampingAndFrictionOnlyTakeEnergy) {
    World world(std::make_shared<StaticWorld>(), without_gravity());
    const CarSpec spec = free_space_car();
    world.add_car(spec, moving({0.0, 0.0, 0.0}, 0.0, {0.0, 0.0, 6.0}));
    world.add_car(spec, moving({1.0, 0.2, 7.0}, 0.5, {-1.5, 0.0, -4.0}));
    const double before = kinetic_energy(world);

    ASSERT_GT(collide(world), 0) << "the cars never touched";
    EXPECT_LT(kinetic_energy(world), 0.99 * before);
}

// 500 km/h each way, nose to nose, straight and off centre: the impulse stops the cars'
// approach at their first touch. Their ellipsoids sink no deeper than a tenth of a metre
// (half the thinnest semi-axis, 0.2 m) and a sub-step's travel (7 cm) into each other at
// any sub-step, so they never pass through; at the end they are apart.
class HeadOn : public testing::TestWithParam<double> {};

TEST_P(HeadOn, At500PlusKmhNeverPassesThrough) {
    const double offset = GetParam();  // m sideways between the two cars' centres
    const double speed = 500.0 / 3.6;
    World world(std::make_shared<StaticWorld>(), without_gravity());
    const CarSpec spec = free_space_car();
    world.add_car(spec, moving({0.0, 0.0, 0.0}, 0.0, {0.0, 0.0, speed}));
    world.add_car(spec, moving({offset, 0.0, 10.0}, std::numbers::pi, {0.0, 0.0, -speed}));

    double deepest = 0.0;
    for (int update = 0; update < 100; ++update) {
        world.update();
        deepest = std::max(deepest, world.last_profile().max_car_penetration);
    }
    EXPECT_GT(deepest, 0.0) << "the cars never touched";
    EXPECT_LT(deepest, 0.17);
    EXPECT_EQ(world.car_resets(0) + world.car_resets(1), 0u);
    for (std::size_t i = 0; i < spec.ellipsoids.size(); ++i)
        for (std::size_t j = 0; j < spec.ellipsoids.size(); ++j)
            EXPECT_LT(ellipsoid_ellipsoid_contact(world.car(0).world_ellipsoid(i),
                                                  world.car(1).world_ellipsoid(j))
                          .depth,
                      0.0);
    if (offset == 0.0) {
        EXPECT_LT(world.car(0).state().position.z, world.car(1).state().position.z);
        EXPECT_LE(world.car(0).state().linear_velocity.z - world.car(1).state().linear_velocity.z,
                  0.0);
    }
}

INSTANTIATE_TEST_SUITE_P(CarContact, HeadOn, testing::Values(0.0, 0.9));

// A car dropped onto another's roof: its floor pan lands on the other's cabin, bounces a
// little, and then rests there, both cars standing still: friction holds it, nothing
// chatters. (The stack's sway on the lower car's suspension is lightly damped: after 12 s
// the upper car moves below 1 mm/s.)
TEST(CarContact, CarOnAnotherRoofSettlesAndStays) {
    World world(test::static_world_of(test::flat_grid(40.0, 40)));
    const CarSpec spec = CarSpec::default_car();
    const double ground = spec.lowest_point_depth() + 0.001;
    world.add_car(spec, moving({0.0, ground, 0.0}, 0.0, glm::dvec3(0.0)));
    // Cabin top 0.75 m above the lower car's centre, floor pan 0.25 m below the upper's.
    world.add_car(spec, moving({0.0, ground + 1.05, 0.0}, 0.0, glm::dvec3(0.0)));
    for (int update = 0; update < 1200; ++update) world.update();

    double fastest = 0.0;
    const glm::dvec3 settled = world.car(1).state().position;
    for (int update = 0; update < 100; ++update) {
        world.update();
        for (std::size_t i = 0; i < 2; ++i)
            fastest = std::max(fastest, glm::length(world.car(i).state().linear_velocity));
    }
    EXPECT_LT(fastest, 1e-3) << "m/s";
    EXPECT_LT(glm::length(world.car(1).state().position - settled), 1e-3);
    EXPECT_GT(world.car(1).state().position.y - world.car(0).state().position.y, 0.9)
        << "the upper car fell off";
    EXPECT_GT(world.last_profile().car_contacts, 0u);
    EXPECT_LT(world.last_profile().max_car_penetration, 0.01);
}

// A car put into another (a respawn on a busy track): add_car and teleport_car refuse it, as
// they refuse one inside the road, and a car beside the other, or back where it was, is fine.
TEST(CarContact, AddCarAndTeleportRefuseACarInsideAnother) {
    World world(std::make_shared<StaticWorld>(), without_gravity());
    const CarSpec spec = free_space_car();
    world.add_car(spec, moving({0.0, 0.0, 0.0}, 0.0, glm::dvec3(0.0)));
    EXPECT_NE(test::error_of([&] {
                  world.add_car(spec, moving({1.0, 0.0, 0.0}, 0.0, {}));
              }).find("World::add_car: ellipsoid"),
              std::string::npos);
    EXPECT_EQ(world.car_count(), 1u);
    const RigidBodyState beside = moving({5.0, 0.0, 0.0}, 0.0, glm::dvec3(0.0));
    world.add_car(spec, beside);
    const std::string why = test::error_of([&] {
        world.teleport_car(1, moving({0.0, 0.0, 1.0}, 0.0, {}));
    });
    EXPECT_NE(why.find("World::teleport_car: ellipsoid"), std::string::npos) << why;
    EXPECT_NE(why.find("overlaps car 0's ellipsoid"), std::string::npos) << why;
    EXPECT_EQ(world.car(1).state().position, beside.position);
    EXPECT_NO_THROW(world.teleport_car(1, beside));
}

// The spring between two cars is checked against the sub-step as the road's springs are:
// two default cars at 60 updates a second of 2 x 1 sub-steps (8.3 ms), whose road springs
// hold, would gain energy at every touch (a 10 km/h bump became 56 km/h).
TEST(CarContact, AddCarRefusesACarSpringTooStiffForTheSubStep) {
    WorldSettings coarse = without_gravity();
    coarse.dt_update = 1.0 / 60.0;
    coarse.steps = 2;
    coarse.substeps = 1;
    World world(std::make_shared<StaticWorld>(), coarse);
    const CarSpec spec = free_space_car();
    world.add_car(spec, moving({0.0, 0.0, 0.0}, 0.0, glm::dvec3(0.0)));
    const std::string why = test::error_of([&] {
        world.add_car(spec, moving({10.0, 0.0, 0.0}, 0.0, {}));
    });
    EXPECT_NE(why.find("World::add_car: CarSpec.car_contact (the mean of this car's and car 0's"),
              std::string::npos)
        << why;
    EXPECT_EQ(world.car_count(), 1u);
}

}  // namespace
}  // namespace trackphys
