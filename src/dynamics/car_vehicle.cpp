// Car::vehicle_wrench: the contact wrench of a car with a vehicle model. Body ellipsoids
// and aerodynamics are as for the arcade car; each wheel's tangential force comes from
// its tyre (docs/vehicle.md), in the frame the exact contact gives it.

#include <glm/geometric.hpp>

#include "dynamics/body_axes.hpp"
#include "trackphys/dynamics/car.hpp"
#include "vehicle/vehicle_access.hpp"

namespace trackphys {

Wrench Car::vehicle_wrench(std::span<const Contact> deepest, std::span<const double> grip,
                           const WheelLoads& wheel_loads, const detail::BodyAxes& axes, double h) {
    Vehicle& vehicle = *vehicle_;
    const double speed_now = speed();
    const glm::dvec3& forward = axes.forward;
    detail::VehicleAccess::begin_substep(vehicle, inputs_.throttle, inputs_.brake, speed_now,
                                         glm::dot(state_.linear_velocity, forward), h);
    Wrench wrench;
    // A body ellipsoid, or a wheel that cannot roll: pushed like the arcade car's body.
    const auto add_body_contact = [&](const Contact& contact, double surface_grip) {
        wrench.add_at_point(
            body_contact_force(on_surface(spec_.body_contact, surface_grip), contact.depth,
                               contact.normal, point_velocity(state_, contact.point)),
            contact.point, state_.position);
    };
    // Every front wheel steers by the same angle and every rear wheel points ahead: two
    // headings per sub-step, each computed when its first wheel needs it.
    glm::dvec3 headings[2];
    bool heading_known[2] = {false, false};
    const auto heading_of = [&](std::size_t i) -> const glm::dvec3& {
        const Axle axle = axle_of(i);
        const int k = static_cast<int>(axle);
        if (!heading_known[k]) headings[k] = wheel_heading(axle, forward), heading_known[k] = true;
        return headings[k];
    };
    for (std::size_t i = 0; i < deepest.size(); ++i) {
        const Contact& contact = deepest[i];
        const bool touching = contact.depth > 0.0;
        const double surface_grip = grip.empty() ? 1.0 : grip[i];
        const int slot = vehicle.wheel_slot(i);
        if (slot < 0) {
            if (touching) add_body_contact(contact, surface_grip);
            continue;
        }
        const auto w = static_cast<std::size_t>(slot);
        // A wheel pressed on its side (heading along the normal) has no rolling direction
        // and only slides: it carries no load into the tyre model then.
        const glm::dvec3& heading = heading_of(i);
        const glm::dvec3 in_plane = heading - contact.normal * glm::dot(heading, contact.normal);
        const double in_plane_length = glm::length(in_plane);
        const WheelLoad& wheel = wheel_loads[i];  // measure_wheel_loads
        const bool rolling = touching && wheel.load > 0.0 && in_plane_length >= 1e-6;
        if (!rolling) {
            detail::VehicleAccess::wheel_force(vehicle, w, 0.0, 0.0, 0.0, h);
            if (touching) add_body_contact(contact, surface_grip);
            continue;
        }
        const glm::dvec3 rolling_direction = in_plane * (1.0 / in_plane_length);  // one division
        const glm::dvec3 lateral = glm::cross(contact.normal, rolling_direction);
        const TyreForce tyre = detail::VehicleAccess::wheel_force(
            vehicle, w, wheel.load, glm::dot(wheel.velocity, rolling_direction),
            glm::dot(wheel.velocity, lateral), h, surface_grip);
        wrench.add_at_point(contact.normal * wheel.load + rolling_direction * tyre.longitudinal +
                                lateral * tyre.lateral,
                            contact.point, state_.position);
    }
    add_aero_force(wrench, speed_now, axes.forward, axes.down);
    return wrench;
}

}  // namespace trackphys
