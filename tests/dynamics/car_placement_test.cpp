#include <random>
#include <vector>

#include <gtest/gtest.h>

#include <glm/gtc/quaternion.hpp>

#include "dynamics/car_access.hpp"
#include "support/same_bits.hpp"
#include "trackphys/dynamics/car.hpp"

namespace trackphys {
namespace {

using test::same_bits;

// Car::world_ellipsoid lifts each wheel by its suspension without glm's products by zero
// and writes only what a motion changes; it must give the bits of the plain formula, the
// body ellipsoid carried by the car's motion with the wheel lifted along the body's up axis.
TEST(CarPlacement, GivesTheBitsOfThePlainRotation) {
    std::mt19937_64 rng(16);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    const CarSpec spec = CarSpec::default_car();
    for (int trial = 0; trial < 2000; ++trial) {
        RigidBodyState state;
        state.position = glm::dvec3(unit(rng), unit(rng), unit(rng)) * 500.0;
        state.orientation = glm::normalize(glm::dquat(unit(rng), unit(rng), unit(rng), unit(rng)));
        Car car(spec, state);
        std::vector<double> travel(car.ellipsoid_count(), 0.0);
        for (std::size_t i = 0; i < travel.size(); ++i)
            if (spec.ellipsoids[i].role != EllipsoidRole::body)
                travel[i] = (0.5 + 0.5 * unit(rng)) * spec.suspension.travel;
        detail::CarAccess::set_suspension(car, travel);
        const glm::dquat& q = car.state().orientation;
        for (std::size_t i = 0; i < car.ellipsoid_count(); ++i) {
            const glm::dvec3 lift = q * glm::dvec3(0.0, travel[i], 0.0);
            const Ellipsoid want =
                car.body_ellipsoid(i).transformed(q, car.state().position + lift);
            const Ellipsoid got = car.world_ellipsoid(i);
            ASSERT_TRUE(same_bits(got.center(), want.center())) << "trial " << trial << ", " << i;
            ASSERT_EQ(got.sorted_radii(), want.sorted_radii());
            ASSERT_EQ(got.sorted_axes(), want.sorted_axes());
        }
    }
}

// Two cars are tested against each other only when their bounding spheres meet, so the
// sphere must hold a wheel raised by its suspension too: here the front wheels, moved
// level with the centre of mass and forward of the body, reach farthest at full travel
// (a review: the sphere taken at full droop let two such cars sink 8 mm unseen).
TEST(CarPlacement, TheBoundingSphereHoldsTheWheelsAtFullTravel) {
    CarSpec spec = CarSpec::default_car();
    for (CarEllipsoid& e : spec.ellipsoids)
        if (e.role == EllipsoidRole::front_wheel) e.center = {e.center.x + 2.0, 0.0, e.center.z};
    ASSERT_EQ(spec.validate(), "");
    Car car(spec, RigidBodyState{});
    std::vector<double> travel(car.ellipsoid_count(), 0.0);
    for (std::size_t i = 0; i < travel.size(); ++i)
        if (spec.ellipsoids[i].role != EllipsoidRole::body) travel[i] = spec.suspension.travel;
    detail::CarAccess::set_suspension(car, travel);
    for (std::size_t i = 0; i < car.ellipsoid_count(); ++i) {
        const Ellipsoid placed = car.world_ellipsoid(i);
        EXPECT_LE(glm::length(placed.center()) + placed.bounding_radius(), car.bounding_radius())
            << "ellipsoid " << i;
    }
}

}  // namespace
}  // namespace trackphys
