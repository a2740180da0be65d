// Car::share_ellipsoids_with: cars whose ellipsoids hold the same bits read one copy, any
// other car keeps its own.

#include <gtest/gtest.h>

#include "dynamics/car_access.hpp"
#include "support/shared_ellipsoids.hpp"
#include "trackphys/dynamics/car.hpp"

namespace trackphys {
namespace {

using test::share_one_copy;

TEST(CarSharing, CarsOfOneSpecShareOnRequest) {
    const CarSpec spec = CarSpec::default_car();
    const Car first(spec, RigidBodyState{});
    Car second(spec, RigidBodyState{});
    EXPECT_FALSE(share_one_copy(first, second)) << "each car builds its own copy";
    EXPECT_TRUE(detail::CarAccess::share_ellipsoids_with(second, first));
    EXPECT_TRUE(share_one_copy(first, second));
    const Car copy = second;
    EXPECT_TRUE(share_one_copy(first, copy)) << "a copy of a car shares what the car shares";
}

// A spec that differs in anything the shared copy holds keeps its own, even where the
// values compare equal (-0.0 == 0.0) but the bits do not; one that differs elsewhere shares.
TEST(CarSharing, OnlyTheSameBitsShare) {
    const CarSpec spec = CarSpec::default_car();
    const Car first(spec, RigidBodyState{});

    CarSpec wider = spec;
    wider.ellipsoids[0].semi_axes.x *= 1.01;
    CarSpec negative_zero = spec;
    ASSERT_EQ(negative_zero.ellipsoids[4].center.x, 0.0);
    negative_zero.ellipsoids[4].center.x = -0.0;
    CarSpec shallower = spec;  // the same ellipsoids, another deep-contact depth
    shallower.deep_contact_fraction *= 0.5;
    CarSpec fewer = spec;
    fewer.ellipsoids.pop_back();
    for (const CarSpec& other : {wider, negative_zero, shallower, fewer}) {
        Car car(other, RigidBodyState{});
        EXPECT_FALSE(detail::CarAccess::share_ellipsoids_with(car, first));
        EXPECT_FALSE(share_one_copy(first, car));
    }

    CarSpec heavier = spec;
    heavier.mass.mass *= 1.2;
    Car car(heavier, RigidBodyState{});
    EXPECT_TRUE(detail::CarAccess::share_ellipsoids_with(car, first));
}

}  // namespace
}  // namespace trackphys
