#pragma once

#include <algorithm>
#include <limits>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "trackphys/dynamics/car_spec.hpp"
#include "trackphys/export.hpp"
#include "trackphys/math/types.hpp"

namespace trackphys {

/// The penalty-contact force laws (docs/design.md#dynamics). Inputs are one ellipsoid's
/// deepest contact: depth d (m, > 0 overlapping), unit push direction n (world, the way
/// the ellipsoid must move to separate) and the velocity of the car's material point at the
/// contact (m/s). Every law returns the world force on the car at that point (N).

/// Normal force magnitude max(0, k d - c v_n): a spring with damping that never pulls.
inline double normal_force(const ContactMaterial& material, double depth, const glm::dvec3& normal,
                           const glm::dvec3& velocity) {
    if (!(depth > 0.0)) return 0.0;
    const double approach = glm::dot(velocity, normal);
    return std::max(0.0, material.stiffness * depth - material.damping * approach);
}

/// A body ellipsoid: normal force plus regularised Coulomb friction opposite the
/// tangential slip, mu F_n beyond material.slip_speed and linear below it (so a car at rest
/// stays at rest instead of chattering).
TRACKPHYS_API glm::dvec3 body_contact_force(const ContactMaterial& material, double depth,
                                            const glm::dvec3& normal, const glm::dvec3& velocity);

/// What a wheel asks of the road this sub-step.
struct WheelCommand {
    glm::dvec3 heading{0.0, 0.0, 1.0};  ///< world direction the wheel rolls in (steered)
    double drive_force = 0.0;           ///< N forward along the heading (>= 0)
    double brake_force = 0.0;           ///< N against the rolling velocity (>= 0)
    /// Drive minus brake is at most this force either way (N): traction control and
    /// anti-lock brakes set it from the grip of the axle's least loaded wheel.
    double max_along_force = std::numeric_limits<double>::infinity();
};

/// A wheel: normal force; drive and brake (together up to max_along_force) along the heading
/// projected onto the contact plane; lateral grip as regularised Coulomb friction against sideways
/// slip; the tangential total limited to the friction circle mu F_n.
TRACKPHYS_API glm::dvec3 wheel_contact_force(const ContactMaterial& material, double depth,
                                             const glm::dvec3& normal, const glm::dvec3& velocity,
                                             const WheelCommand& command);

/// The same for a wheel whose normal force is known: pressing = normal_force(material,
/// depth, normal, velocity), as a car measures its wheel loads before their forces.
TRACKPHYS_API glm::dvec3 pressed_wheel_force(const ContactMaterial& material, double pressing,
                                             const glm::dvec3& normal, const glm::dvec3& velocity,
                                             const WheelCommand& command);

}  // namespace trackphys
