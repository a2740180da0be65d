#include "trackphys/dynamics/rigid_body.hpp"

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

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

}  // namespace

void integrate(RigidBodyState& state, const MassProperties& mass, const Wrench& wrench,
               const glm::dvec3& gravity, double h) {
    state.linear_velocity += h * (wrench.force / mass.mass + gravity);

    const glm::dvec3 momentum =
        apply_inertia(state.orientation, mass.principal_inertia, state.angular_velocity);
    const glm::dvec3 gyroscopic = glm::cross(state.angular_velocity, momentum);
    state.angular_velocity += h * apply_inverse_inertia(state.orientation, mass.principal_inertia,
                                                        wrench.torque - gyroscopic);

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
