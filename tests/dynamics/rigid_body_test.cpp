#include "trackphys/dynamics/rigid_body.hpp"

#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

namespace trackphys {
namespace {

const glm::dvec3 gravity(0.0, -9.81, 0.0);

// Semi-implicit Euler under constant acceleration a has a closed form after n steps:
// v_n = v_0 + n h a, x_n = x_0 + n h v_0 + h^2 a n (n + 1) / 2.
TEST(RigidBody, FreeFallMatchesTheSchemesClosedForm) {
    RigidBodyState state;
    state.position = {1.0, 100.0, -2.0};
    state.linear_velocity = {3.0, 4.0, 0.0};
    const MassProperties mass = MassProperties::solid_box(1200.0, {2.0, 1.2, 4.5});
    const double h = 0.25e-3;
    const int n = 4000;
    for (int i = 0; i < n; ++i) integrate(state, mass, Wrench{}, gravity, h);

    const double t = n * h;
    EXPECT_NEAR(state.linear_velocity.y, 4.0 - 9.81 * t, 1e-9);
    EXPECT_NEAR(state.position.x, 1.0 + 3.0 * t, 1e-9);
    EXPECT_NEAR(state.position.y, 100.0 + 4.0 * t - 9.81 * h * h * n * (n + 1) / 2.0, 1e-9);
    EXPECT_EQ(state.orientation, glm::dquat(1.0, 0.0, 0.0, 0.0));
}

TEST(RigidBody, ConstantTorqueAboutAPrincipalAxisSpinsUpLinearly) {
    RigidBodyState state;
    const MassProperties mass{2.0, {0.5, 0.8, 1.1}};
    Wrench wrench;
    wrench.torque = {0.0, 0.4, 0.0};  // about y, where I = 0.8
    const double h = 1e-3;
    for (int i = 0; i < 1000; ++i) integrate(state, mass, wrench, glm::dvec3(0.0), h);
    EXPECT_NEAR(state.angular_velocity.y, 0.4 / 0.8 * 1.0, 1e-12);
    EXPECT_NEAR(glm::length(state.orientation), 1.0, 1e-15);
    // Angle turned: sum of omega_k h = alpha h^2 n (n + 1) / 2.
    const double angle = glm::angle(state.orientation);
    EXPECT_NEAR(angle, 0.5 * 1e-6 * 1000 * 1001 / 2.0, 1e-4);
}

TEST(RigidBody, TorqueFreeSpinKeepsEnergyAndMomentum) {
    RigidBodyState state;
    state.angular_velocity = {0.3, 5.0, 0.2};  // near the stable major axis
    const MassProperties mass{1.0, {1.0, 2.0, 3.0}};
    const double energy0 = kinetic_energy(state, mass);
    const glm::dvec3 momentum0 =
        state.orientation *
        (mass.principal_inertia * (glm::conjugate(state.orientation) * state.angular_velocity));
    for (int i = 0; i < 20000; ++i) integrate(state, mass, Wrench{}, glm::dvec3(0.0), 1e-4);
    const glm::dvec3 momentum =
        state.orientation *
        (mass.principal_inertia * (glm::conjugate(state.orientation) * state.angular_velocity));
    EXPECT_NEAR(kinetic_energy(state, mass) / energy0, 1.0, 2e-3);
    EXPECT_LT(glm::length(momentum - momentum0) / glm::length(momentum0), 2e-3);
}

// A car's inertia tumbling fast about a tilted axis, as after a crash, for 10 s: with the
// gyroscopic term explicit its energy grew five-fold (50 rad/s at the car's sub-step).
TEST(RigidBody, FastTiltedSpinNeverGainsEnergy) {
    RigidBodyState state;
    state.angular_velocity = {20.0, 40.0, 22.0};  // 50 rad/s
    const MassProperties mass{1200.0, {480.0, 1750.0, 1500.0}};
    const double energy0 = kinetic_energy(state, mass);
    double most = energy0;
    for (int i = 0; i < 40000; ++i) {
        integrate(state, mass, Wrench{}, glm::dvec3(0.0), 2.5e-4);
        most = std::max(most, kinetic_energy(state, mass));
    }
    EXPECT_LE(most, energy0 * (1.0 + 1e-12));
    EXPECT_GT(kinetic_energy(state, mass), 0.5 * energy0) << "the spin was damped away";
}

TEST(RigidBody, WrenchAtAPointAddsTheLeverArmTorque) {
    Wrench wrench;
    wrench.add_at_point({0.0, 10.0, 0.0}, {2.0, 0.0, 0.0}, {0.0, 0.0, 0.0});
    EXPECT_EQ(wrench.force, glm::dvec3(0.0, 10.0, 0.0));
    EXPECT_EQ(wrench.torque, glm::dvec3(0.0, 0.0, 20.0));
    RigidBodyState state;
    state.angular_velocity = {0.0, 1.0, 0.0};
    EXPECT_NEAR(glm::length(point_velocity(state, {1.0, 0.0, 0.0}) - glm::dvec3(0.0, 0.0, -1.0)),
                0.0, 1e-15);
}

TEST(RigidBody, SolidBoxInertia) {
    const MassProperties box = MassProperties::solid_box(12.0, {1.0, 2.0, 3.0});
    EXPECT_DOUBLE_EQ(box.principal_inertia.x, 13.0);
    EXPECT_DOUBLE_EQ(box.principal_inertia.y, 10.0);
    EXPECT_DOUBLE_EQ(box.principal_inertia.z, 5.0);
}

}  // namespace
}  // namespace trackphys
