#include "trackphys/dynamics/car_spec.hpp"

#include <limits>
#include <string>

#include <gtest/gtest.h>

namespace trackphys {
namespace {

TEST(CarSpec, DefaultCarIsValidWithFourWheelsAndFourBodyParts) {
    const CarSpec car = CarSpec::default_car();
    EXPECT_EQ(car.validate(), "");
    EXPECT_EQ(car.ellipsoids.size(), 8u);
    int wheels = 0;
    for (const CarEllipsoid& e : car.ellipsoids) wheels += e.role != EllipsoidRole::body;
    EXPECT_EQ(wheels, 4);
    EXPECT_DOUBLE_EQ(car.mass.mass, 1200.0);
}

TEST(CarSpec, AFlatBodysMomentsPass) {
    // A plate's moments meet I_z = I_x + I_y, up to their rounding.
    CarSpec spec = CarSpec::default_car();
    spec.mass = MassProperties::solid_box(1200.0, {1.9, 4.3, 0.0});
    EXPECT_EQ(spec.validate(), "");
    spec.mass.principal_inertia.z *= 1.0 + 0x1p-30;
    EXPECT_NE(spec.validate(), "");
}

TEST(CarSpec, ValidationNamesTheField) {
    struct Case {
        void (*spoil)(CarSpec&);
        const char* expected;
    };
    const Case cases[] = {
        {[](CarSpec& c) { c.mass.mass = -1.0; },
         "CarSpec.mass.mass must be finite and > 0, got -1"},
        {[](CarSpec& c) { c.mass.principal_inertia.z = 0.0; }, "CarSpec.mass.principal_inertia.z"},
        {[](CarSpec& c) {
             c.mass.principal_inertia = {1.0, 1.0, 100.0};
         },
         "CarSpec.mass.principal_inertia.z is 100, more than the other two moments together (2)"},
        {[](CarSpec& c) {
             c.mass.principal_inertia = {5.0, 1.0, 2.0};
         },
         "CarSpec.mass.principal_inertia.x is 5, more than the other two moments together (3)"},
        {[](CarSpec& c) { c.ellipsoids.clear(); }, "CarSpec.ellipsoids must hold 1 to 64"},
        {[](CarSpec& c) { c.ellipsoids[2].semi_axes.y = 0.0; },
         "CarSpec.ellipsoids[2].semi_axes.y must be finite and > 0, got 0"},
        {[](CarSpec& c) { c.ellipsoids[5].center.x = std::numeric_limits<double>::quiet_NaN(); },
         "CarSpec.ellipsoids[5].center is not finite"},
        {[](CarSpec& c) {
             c.ellipsoids[1].orientation = {0, 0, 0, 0};
         },
         "CarSpec.ellipsoids[1].orientation"},
        {[](CarSpec& c) { c.wheel_contact.stiffness = 0.0; }, "CarSpec.wheel_contact.stiffness"},
        {[](CarSpec& c) { c.car_contact.damping = -1.0; }, "CarSpec.car_contact.damping"},
        {[](CarSpec& c) { c.car_contact.slip_speed = 0.0; }, "CarSpec.car_contact.slip_speed"},
        {[](CarSpec& c) { c.body_contact.friction = -0.1; }, "CarSpec.body_contact.friction"},
        {[](CarSpec& c) { c.max_steer_angle = 2.0; }, "CarSpec.max_steer_angle must be below 1.5"},
        {[](CarSpec& c) { c.drag_area = std::numeric_limits<double>::infinity(); },
         "CarSpec.drag_area"},
        {[](CarSpec& c) { c.max_reverse_speed = std::numeric_limits<double>::quiet_NaN(); },
         "CarSpec.max_reverse_speed must be finite and >= 0"},
        {[](CarSpec& c) {
             c = CarSpec::preset("gt");
             c.vehicle->gearbox.reverse_ratio = -3.0;
         },
         "CarSpec.vehicle.gearbox.reverse_ratio must be finite and > 0, got -3"},
    };
    for (const Case& c : cases) {
        CarSpec spec = CarSpec::default_car();
        c.spoil(spec);
        const std::string why = spec.validate();
        EXPECT_NE(why.find(c.expected), std::string::npos) << "got: " << why;
    }
}

}  // namespace
}  // namespace trackphys
