#include "trackphys/dynamics/contact_force.hpp"

#include <cmath>
#include <limits>
#include <random>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "dynamics/wheel_force.hpp"

namespace trackphys {
namespace {

const glm::dvec3 up(0.0, 1.0, 0.0);
const ContactMaterial material{2.0e5, 1.5e4, 1.2, 0.05};

TEST(ContactForce, SpringAndDamperNeverPull) {
    EXPECT_DOUBLE_EQ(normal_force(material, 0.01, up, glm::dvec3(0.0)), 2000.0);
    EXPECT_DOUBLE_EQ(normal_force(material, 0.01, up, {0, -0.1, 0}), 2000.0 + 1500.0);
    EXPECT_EQ(normal_force(material, 0.01, up, {0, 1.0, 0}), 0.0);    // separating fast
    EXPECT_EQ(normal_force(material, -0.01, up, {0, -1.0, 0}), 0.0);  // not touching
    EXPECT_EQ(normal_force(material, 0.0, up, {0, -1.0, 0}), 0.0);
}

TEST(ContactForce, BodyFrictionOpposesSlipAndIsBoundedByCoulomb) {
    std::mt19937 rng(5);
    std::normal_distribution<double> normal;
    for (int i = 0; i < 10000; ++i) {
        const glm::dvec3 n = glm::normalize(glm::dvec3(normal(rng), normal(rng), normal(rng)));
        const glm::dvec3 v(normal(rng), normal(rng), normal(rng));
        const double depth = 0.02 * std::abs(normal(rng));
        const glm::dvec3 f = body_contact_force(material, depth, n, v);
        const double pressing = normal_force(material, depth, n, v);
        const glm::dvec3 tangential = f - n * glm::dot(f, n);
        const glm::dvec3 slip = v - n * glm::dot(v, n);
        ASSERT_NEAR(glm::dot(f, n), pressing, 1e-9 * (1.0 + pressing));
        ASSERT_LE(glm::length(tangential), material.friction * pressing * (1.0 + 1e-12) + 1e-12);
        ASSERT_LE(glm::dot(tangential, slip), 1e-9);
        if (glm::length(slip) > material.slip_speed) {
            ASSERT_NEAR(glm::length(tangential), material.friction * pressing,
                        1e-6 * (1.0 + pressing));
        }
    }
}

TEST(ContactForce, WheelDrivesBrakesAndGripsWithinTheFrictionCircle) {
    WheelCommand command;
    command.heading = {0.0, 0.0, 1.0};
    const double depth = 0.015;  // 3000 N of spring, grip 3600 N
    // Driving at rest: pushes forward with the drive force.
    command.drive_force = 1000.0;
    glm::dvec3 f = wheel_contact_force(material, depth, up, glm::dvec3(0.0), command);
    EXPECT_NEAR(f.z, 1000.0, 1e-9);
    EXPECT_NEAR(f.y, 3000.0, 1e-9);
    // Too much drive: limited to mu F_n.
    command.drive_force = 1e5;
    f = wheel_contact_force(material, depth, up, glm::dvec3(0.0), command);
    EXPECT_NEAR(f.z, 3600.0, 1e-9);
    // Braking while rolling forward: force backwards.
    command.drive_force = 0.0;
    command.brake_force = 2000.0;
    f = wheel_contact_force(material, depth, up, {0.0, 0.0, 30.0}, command);
    EXPECT_NEAR(f.z, -2000.0, 1e-9);
    // Sliding sideways at speed: full lateral grip against the slide, nothing along.
    command.brake_force = 0.0;
    f = wheel_contact_force(material, depth, up, {5.0, 0.0, 30.0}, command);
    EXPECT_NEAR(f.x, -3600.0, 1e-9);
    EXPECT_NEAR(f.z, 0.0, 1e-9);
    // Rolling straight without drive or brake: no tangential force at all.
    f = wheel_contact_force(material, depth, up, {0.0, 0.0, 30.0}, command);
    EXPECT_EQ(f.x, 0.0);
    EXPECT_EQ(f.z, 0.0);
}

// Car::contact_wrench passes the load it measured with the spec's wheel material: the force
// must be the one the axle's material gives, bit for bit, and must press with the load it
// is given.
TEST(ContactForce, PressedWheelForceIsTheWheelForceOfTheGivenLoad) {
    std::mt19937 rng(11);
    std::normal_distribution<double> normal;
    for (int i = 0; i < 10000; ++i) {
        const glm::dvec3 n = glm::normalize(glm::dvec3(normal(rng), normal(rng), normal(rng)));
        const glm::dvec3 v(10.0 * normal(rng), normal(rng), 30.0 * normal(rng));
        const double depth = 0.02 * normal(rng);
        WheelCommand command;
        command.heading = glm::normalize(glm::dvec3(normal(rng), normal(rng), normal(rng)));
        command.drive_force = 2000.0 * std::abs(normal(rng));
        command.brake_force = 2000.0 * std::abs(normal(rng));
        // The car measures the load with the spec's wheel material and presses an axle's,
        // which differs in friction only.
        ContactMaterial axle = material;
        axle.friction *= 1.15;
        const glm::dvec3 expected = wheel_contact_force(axle, depth, n, v, command);
        const glm::dvec3 got =
            pressed_wheel_force(axle, normal_force(material, depth, n, v), n, v, command);
        ASSERT_EQ(got, expected) << i;
    }
    WheelCommand rolling;
    rolling.heading = {0.0, 0.0, 1.0};
    EXPECT_EQ(pressed_wheel_force(material, 1234.0, up, {0.0, 0.0, 30.0}, rolling),
              glm::dvec3(0.0, 1234.0, 0.0));
    EXPECT_EQ(pressed_wheel_force(material, 0.0, up, {0.0, -1.0, 30.0}, rolling), glm::dvec3(0.0));
}

TEST(ContactForce, WheelOnABankUsesTheHeadingProjectedIntoTheContactPlane) {
    const glm::dvec3 banked = glm::normalize(glm::dvec3(0.5, 1.0, 0.0));
    WheelCommand command;
    command.heading = {0.0, 0.0, 1.0};
    command.drive_force = 500.0;
    const glm::dvec3 f = wheel_contact_force(material, 0.01, banked, glm::dvec3(0.0), command);
    EXPECT_NEAR(f.z, 500.0, 1e-9);
    EXPECT_NEAR(glm::dot(f, banked), 2000.0, 1e-9);
}

// The wheel law takes the hypot only where the shortcut cannot prove a force inside the
// circle, so the shortcut must never prove one outside, at any scale and on the circle's
// edge to the ulp; and inside it must prove all but the last 1e-11 of the radius.
TEST(ContactForce, FrictionCircleShortcutNeverProvesAForceOutside) {
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> exponent(-300.0, 300.0);
    std::uniform_real_distribution<double> angle(-3.2, 3.2);
    std::uniform_real_distribution<double> ratio(0.5, 1.5);
    std::uniform_int_distribution<int> ulps(-40, 40);
    int proved = 0;
    for (int i = 0; i < 400000; ++i) {
        const double grip = std::pow(10.0, exponent(rng));
        const double radius = grip * (i % 2 == 0 ? ratio(rng) : 1.0 + ulps(rng) * 0x1p-52);
        const double a = angle(rng);
        const double along = radius * std::cos(a);
        const double across = radius * std::sin(a);
        const double tangential = std::hypot(along, across);
        const bool inside = detail::inside_friction_circle(along, across, grip);
        if (inside) {
            ASSERT_LE(tangential, grip) << along << " " << across << " " << grip;
        }
        if (grip > 1e-99 && grip < 1e99 && tangential <= grip * (1.0 - 1e-11)) {
            ASSERT_TRUE(inside) << along << " " << across << " " << grip;
        }
        proved += inside;
    }
    EXPECT_GT(proved, 50000);
    const double nan = std::numeric_limits<double>::quiet_NaN();
    EXPECT_FALSE(detail::inside_friction_circle(nan, 0.0, 1.0));
    EXPECT_FALSE(detail::inside_friction_circle(0.0, nan, 1.0));
}

}  // namespace
}  // namespace trackphys
