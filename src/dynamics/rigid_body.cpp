#include "trackphys/dynamics/rigid_body.hpp"

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

namespace trackphys {

MassProperties MassProperties::solid_box(double mass, const glm::dvec3& extents) {
    const glm::dvec3 s = extents * extents;
    return {mass, mass / 12.0 * glm::dvec3(s.y + s.z, s.x + s.z, s.x + s.y)};
}

namespace {

// I_world v = R I_body R^T v, without forming the world tensor.
glm::dvec3 apply_inertia(const glm::dquat& q, const glm::dvec3& principal, const glm::dvec3& v) {
    return q * (principal * (glm::conjugate(q) * v));
}

glm::dvec3 apply_inverse_inertia(const glm::dquat& q, const glm::dvec3& principal,
                                 const glm::dvec3& v) {
    return q * ((glm::conjugate(q) * v) / principal);
}

// [v]x, the matrix of v x .
glm::dmat3 cross_matrix(const glm::dvec3& v) {
    return {0.0, v.z, -v.y, -v.z, 0.0, v.x, v.y, -v.x, 0.0};  // column by column
}

// How h seconds of torque-free motion, I w' = -w x I w, change the body-frame angular
// velocity w, the gyroscopic term implicit: one Newton step from w of I (w1 - w) +
// h w1 x I w1 = 0 (none about a principal axis).
// Explicit, that term feeds energy into any spin about a tilted axis: a car tumbling at
// 50 rad/s after a crash had five times its energy 10 s later.
glm::dvec3 gyroscopic_change(const glm::dvec3& principal, const glm::dvec3& w, double h) {
    const glm::dvec3 momentum = principal * w;
    const glm::dmat3 inertia(principal.x, 0.0, 0.0, 0.0, principal.y, 0.0, 0.0, 0.0, principal.z);
    const glm::dmat3 jacobian = inertia + h * (cross_matrix(w) * inertia - cross_matrix(momentum));
    return -(glm::inverse(jacobian) * (h * glm::cross(w, momentum)));
}

}  // namespace

void integrate(RigidBodyState& state, const MassProperties& mass, const Wrench& wrench,
               const glm::dvec3& gravity, double h) {
    state.linear_velocity += h * (wrench.force / mass.mass + gravity);

    const glm::dvec3 body_spin = glm::conjugate(state.orientation) * state.angular_velocity;
    state.angular_velocity +=
        state.orientation * gyroscopic_change(mass.principal_inertia, body_spin, h) +
        h * apply_inverse_inertia(state.orientation, mass.principal_inertia, wrench.torque);

    state.position += h * state.linear_velocity;
    const glm::dquat spin(0.0, state.angular_velocity);
    state.orientation = glm::normalize(state.orientation + (0.5 * h) * (spin * state.orientation));
}

double kinetic_energy(const RigidBodyState& state, const MassProperties& mass) {
    const glm::dvec3 momentum =
        apply_inertia(state.orientation, mass.principal_inertia, state.angular_velocity);
    return 0.5 * mass.mass * glm::dot(state.linear_velocity, state.linear_velocity) +
           0.5 * glm::dot(state.angular_velocity, momentum);
}

}  // namespace trackphys
