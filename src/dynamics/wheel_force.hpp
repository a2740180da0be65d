#pragma once

// The force laws a car's sub-step calls per wheel, defined here so that Car::contact_wrench
// compiles them into its loop rather than passing each wheel's material, command and force
// through memory in a call. The exported laws in contact_force.hpp call these.

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "trackphys/dynamics/contact_force.hpp"

namespace trackphys::detail {

// Coulomb friction, regularised: the full mu F_n opposes slips faster than slip_speed and
// scales linearly below it, which acts as a strong viscous damper at rest.
inline glm::dvec3 regularised_friction(double limit, double slip_speed, const glm::dvec3& slip) {
    const double speed = glm::length(slip);
    if (speed == 0.0) return glm::dvec3(0.0);
    return slip * (-limit / std::max(speed, slip_speed));
}

// Whether hypot(along, across) <= grip, proved without the hypot; false when it cannot be
// (then the hypot decides). hypot <= |along| + |across|, equal only when one is 0 (then both
// are exact), so a sum 1e-12 inside the grip proves it (most sub-steps of a lap). Failing
// that, a sum of squares 1e-12 inside the grip's square does (nearly all the rest): its
// roundings are a few parts in 1e16, far inside the margin, for a grip whose square is
// neither subnormal nor beyond double's range, and a NaN fails both tests.
inline bool inside_friction_circle(double along, double across, double grip) {
    if (std::abs(along) + std::abs(across) <= grip * (1.0 - 1e-12)) return true;
    return grip > 1e-100 && grip < 1e100 &&
           along * along + across * across <= grip * grip * (1.0 - 1e-12);
}

// The law behind trackphys::pressed_wheel_force (contact_force.hpp), which calls this.
inline glm::dvec3 pressed_wheel_force(const ContactMaterial& material, double pressing,
                                      const glm::dvec3& normal, const glm::dvec3& velocity,
                                      const WheelCommand& command) {
    if (pressing == 0.0) return glm::dvec3(0.0);
    const double grip = material.friction * pressing;

    // Rolling direction in the contact plane; a wheel pressed on its side (heading along
    // the normal) has none and only slides.
    const glm::dvec3 in_plane = command.heading - normal * glm::dot(command.heading, normal);
    const double in_plane_length = glm::length(in_plane);
    const glm::dvec3 slip = velocity - normal * glm::dot(velocity, normal);
    if (in_plane_length < 1e-6)
        return normal * pressing + regularised_friction(grip, material.slip_speed, slip);
    const glm::dvec3 forward = in_plane / in_plane_length;
    const glm::dvec3 lateral = glm::cross(normal, forward);

    const double rolling_speed = glm::dot(slip, forward);
    const double sideways_speed = glm::dot(slip, lateral);
    const double brake =
        command.brake_force * std::clamp(rolling_speed / material.slip_speed, -1.0, 1.0);
    double along =
        std::clamp(command.drive_force - brake, -command.max_along_force, command.max_along_force);
    double across = -grip * std::clamp(sideways_speed / material.slip_speed, -1.0, 1.0);

    // Friction circle: the tyre cannot transmit more than mu F_n in total.
    if (!inside_friction_circle(along, across, grip)) {
        const double tangential = std::hypot(along, across);
        if (tangential > grip) {
            along *= grip / tangential;
            across *= grip / tangential;
        }
    }
    return normal * pressing + forward * along + lateral * across;
}

}  // namespace trackphys::detail
