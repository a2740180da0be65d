#include "trackphys/dynamics/contact_force.hpp"

#include <glm/geometric.hpp>

#include "dynamics/wheel_force.hpp"

namespace trackphys {

glm::dvec3 body_contact_force(const ContactMaterial& material, double depth,
                              const glm::dvec3& normal, const glm::dvec3& velocity) {
    const double pressing = normal_force(material, depth, normal, velocity);
    if (pressing == 0.0) return glm::dvec3(0.0);
    const glm::dvec3 slip = velocity - normal * glm::dot(velocity, normal);
    return normal * pressing +
           detail::regularised_friction(material.friction * pressing, material.slip_speed, slip);
}

glm::dvec3 wheel_contact_force(const ContactMaterial& material, double depth,
                               const glm::dvec3& normal, const glm::dvec3& velocity,
                               const WheelCommand& command) {
    return pressed_wheel_force(material, normal_force(material, depth, normal, velocity), normal,
                               velocity, command);
}

glm::dvec3 pressed_wheel_force(const ContactMaterial& material, double pressing,
                               const glm::dvec3& normal, const glm::dvec3& velocity,
                               const WheelCommand& command) {
    return detail::pressed_wheel_force(material, pressing, normal, velocity, command);
}

}  // namespace trackphys
