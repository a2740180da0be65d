#pragma once

#include <string>
#include <vector>

#include <glm/gtc/quaternion.hpp>
#include <glm/vec3.hpp>

#include "trackphys/dynamics/rigid_body.hpp"
#include "trackphys/export.hpp"

namespace trackphys {

/// What one of the car's ellipsoids does when it touches the road.
enum class EllipsoidRole {
    body,        ///< chassis: spring-damper contact with plain Coulomb friction
    front_wheel, ///< steered wheel: rolls along its heading, lateral grip
    rear_wheel,  ///< driven wheel: rolls, takes drive and brake, lateral grip
};

/// One ellipsoid of the car, fixed in the body frame (+Z forward, +Y up, +X left), relative
/// to the centre of mass. Wheels do not spin as bodies of their own: rolling, drive, brake
/// and grip are forces at the contact (DESIGN.md, "Dynamics").
struct CarEllipsoid {
    glm::dvec3 center{0.0};                       ///< body frame (m)
    glm::dvec3 semi_axes{0.3};                    ///< along its own local axes (m), all > 0
    glm::dquat orientation{1.0, 0.0, 0.0, 0.0};   ///< body from ellipsoid local
    EllipsoidRole role = EllipsoidRole::body;
};

/// Penalty contact law (per ellipsoid): normal force max(0, k d - c v_n) and regularised
/// Coulomb friction mu F_n, full strength beyond slip_speed.
struct ContactMaterial {
    double stiffness = 2.0e5;   ///< k, N/m
    double damping = 1.5e4;     ///< c, N s/m
    double friction = 1.0;      ///< mu, dimensionless
    double slip_speed = 0.05;   ///< m/s of slip at which friction reaches mu F_n
};

/// Everything that defines a car. Start from CarSpec::default_car() and change fields;
/// validate() (or Car's constructor) names any field that is out of range.
struct TRACKPHYS_API CarSpec {
    MassProperties mass;
    std::vector<CarEllipsoid> ellipsoids;
    ContactMaterial body_contact;
    ContactMaterial wheel_contact;
    double max_drive_force = 2.0e4;     ///< N at the driven wheels, below the power limit
    double max_drive_power = 6.0e6;     ///< W: drive force is min(max_drive_force, P / v)
    double max_brake_force = 3.0e4;     ///< N over all wheels, bounded by grip
    double max_steer_angle = 0.6;       ///< rad at full steer, at low speed
    double drag_area = 0.35;            ///< C_d A (m^2): drag 1/2 rho C_d A v^2
    double downforce_area = 0.9;        ///< C_l A (m^2): downforce 1/2 rho C_l A v^2
    double air_density = 1.2;           ///< kg/m^3

    /// A 1200 kg car, 4.5 m long and 2 m wide: four wheels (0.35 m radius, 0.15 m half
    /// width) and four body ellipsoids, springs for about 1.5 cm static sag, damping near
    /// critical, enough power and downforce to reach 1000 km/h.
    static CarSpec default_car();

    /// Empty when every field is in range; otherwise the first problem, naming the field
    /// (e.g. "CarSpec.ellipsoids[2].semi_axes.y must be finite and > 0, got 0").
    std::string validate() const;
};

}  // namespace trackphys
