#pragma once

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include "trackphys/export.hpp"
#include "trackphys/math/types.hpp"

namespace trackphys {

/// Where a rigid body is and how it moves: the state the integrator advances and a
/// snapshot saves. Position is the centre of mass in world space (m); orientation maps
/// body to world; velocities are world-space (m/s, rad/s).
struct RigidBodyState {
    glm::dvec3 position{0.0};
    glm::dquat orientation{1.0, 0.0, 0.0, 0.0};
    glm::dvec3 linear_velocity{0.0};
    glm::dvec3 angular_velocity{0.0};
};

/// Mass properties: mass (kg) and the inertia tensor about the centre of mass in the body
/// frame (kg m^2), diagonal because body axes are chosen as principal axes.
struct MassProperties {
    double mass = 1.0;
    glm::dvec3 principal_inertia{1.0};

    /// A solid box of the given full extents (m): I_x = m (h_y^2 + h_z^2) / 12, etc.
    static MassProperties solid_box(double mass, const glm::dvec3& extents);
};

/// Force and torque gathered over one sub-step, in world space, about the centre of mass.
struct Wrench {
    glm::dvec3 force{0.0};   ///< N
    glm::dvec3 torque{0.0};  ///< N m

    /// Adds force f acting at world point p on a body whose centre of mass is at com.
    void add_at_point(const glm::dvec3& f, const glm::dvec3& p, const glm::dvec3& com) {
        force += f;
        torque += glm::cross(p - com, f);
    }
};

/// Advances state by h seconds under the wrench and gravity with semi-implicit (symplectic)
/// Euler: velocities first, then positions with the new velocities. Angular velocity
/// follows Euler's equations, the gyroscopic term omega x (I omega) implicit in the body
/// frame (one Newton step), so a free spin does not gain energy (it loses a little, as
/// (h omega)^2); the orientation takes q += h/2 (0, omega) q and is renormalised.
TRACKPHYS_API void integrate(RigidBodyState& state, const MassProperties& mass,
                             const Wrench& wrench, const glm::dvec3& gravity, double h);

/// The world-space velocity of the body point currently at world position p (m/s).
inline glm::dvec3 point_velocity(const RigidBodyState& state, const glm::dvec3& p) {
    return state.linear_velocity + glm::cross(state.angular_velocity, p - state.position);
}

/// Kinetic energy (J): 1/2 m v^2 + 1/2 omega . I_world omega.
TRACKPHYS_API double kinetic_energy(const RigidBodyState& state, const MassProperties& mass);

}  // namespace trackphys
