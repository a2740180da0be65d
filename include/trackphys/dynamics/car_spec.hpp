#pragma once

#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <glm/gtc/quaternion.hpp>
#include <glm/vec3.hpp>

#include "trackphys/dynamics/rigid_body.hpp"
#include "trackphys/export.hpp"
#include "trackphys/math/types.hpp"
#include "trackphys/vehicle/vehicle_spec.hpp"

namespace trackphys {

/// What one of the car's ellipsoids does when it touches the road.
enum class EllipsoidRole {
    body,         ///< chassis: spring-damper contact with plain Coulomb friction
    front_wheel,  ///< steered wheel: rolls along its heading, drive, brake, lateral grip
    rear_wheel,   ///< fixed wheel: rolls, drive, brake, lateral grip
};

/// One ellipsoid of the car, fixed in the body frame (+Z forward, +Y up, +X left), relative
/// to the centre of mass. Wheels do not spin as bodies of their own: rolling, drive, brake
/// and grip are forces at the contact (docs/design.md#dynamics).
struct CarEllipsoid {
    glm::dvec3 center{0.0};                      ///< body frame (m)
    glm::dvec3 semi_axes{0.3};                   ///< along its own local axes (m), all > 0
    glm::dquat orientation{1.0, 0.0, 0.0, 0.0};  ///< body from ellipsoid local
    EllipsoidRole role = EllipsoidRole::body;
};

/// Penalty contact law (per ellipsoid): normal force max(0, k d - c v_n) and regularised
/// Coulomb friction mu F_n, full strength beyond slip_speed.
struct ContactMaterial {
    double stiffness = 2.0e5;  ///< k, N/m
    double damping = 1.5e4;    ///< c, N s/m
    double friction = 1.0;     ///< mu, dimensionless
    double slip_speed = 0.05;  ///< m/s of slip at which friction reaches mu F_n
};

/// Each wheel hangs on a spring-damper that lets it move along the body's up axis, so that
/// all four stay on a road that twists under the car. The wheel is massless: its travel s
/// (compression from full droop, m) follows c ds/dt = F_up - k s, where F_up is the tyre's
/// normal force along the body's up axis, and the body feels the tyre force itself.
struct Suspension {
    double stiffness = 6.0e4;  ///< k, N/m per wheel: about 5 cm of sag under the default car
    double damping = 6.0e3;    ///< c, N s/m per wheel
    double travel = 0.12;      ///< m from full droop to the bump stop
};

/// Everything that defines a car. Start from CarSpec::default_car() and change fields;
/// validate() (or Car's constructor) names any field that is out of range.
struct TRACKPHYS_API CarSpec {
    /// The most ellipsoids a car may have.
    static constexpr std::size_t max_ellipsoids = 64;
    /// The farthest an ellipsoid's centre may lie from the centre of mass, and its longest
    /// semi-axis (m): far beyond any vehicle, near enough that the checks' squares of them
    /// stay finite.
    static constexpr double max_extent = 1.0e4;
    /// A negative throttle drives a car backwards only below this forward speed (m/s):
    /// nearly stopped or already rolling backwards; a vehicle model in reverse gear goes
    /// back to first under a positive throttle only below this speed backwards (CarInputs).
    /// The arcade car reads its body's forward speed, the vehicle model its wheels' mean
    /// rolling speed, as a gearbox does.
    static constexpr double reverse_engage_speed = 1.0;

    MassProperties mass;
    std::vector<CarEllipsoid> ellipsoids;
    ContactMaterial body_contact;
    ContactMaterial wheel_contact;
    /// Contact with another car, for every ellipsoid (wheels too: a bump between cars is
    /// no tyre force). A pair of cars uses the mean of their two materials, so the law is
    /// the same seen from either car. Stiffer than the road contacts: two cars closing at
    /// 10 m/s sink at most 2.4 cm into each other (v sqrt(m_pair / k), m_pair = 600 kg); faster
    /// impacts are stopped by the deep-contact impulse (see World).
    ContactMaterial car_contact{1.0e8, 1.0e5, 0.5, 0.001};
    // The drive, brake and grip fields below marked "arcade" are the arcade car's: a car with
    // a vehicle model (CarSpec::vehicle) takes its torque, brakes and grip from the model's
    // engine, brake torque and tyres, and ignores them (a printed gt spec lists them all).

    /// Arcade: the rear tyres are wider: their friction is wheel_contact.friction times this. With
    /// tyres whose grip is proportional to load, both axles would saturate together and the
    /// car would be on the edge of a spin at every limit; more grip at the rear makes it
    /// understeer instead, as road cars are set up to.
    double rear_grip_factor = 1.15;
    Suspension suspension;
    double max_drive_force = 2.0e4;  ///< arcade: N over all wheels, below the power limit
    /// Share of the drive force at the front wheels (0 = rear-wheel drive, 1 = front).
    double front_drive_share = 0.4;
    /// Arcade: traction control and anti-lock brakes: a wheel's drive or brake force is at most
    /// this share of its grip mu F_n, so that a spinning or locked wheel never uses up the
    /// lateral grip that keeps the car on its line.
    double traction_limit = 0.8;
    double max_drive_power = 6.0e6;  ///< arcade: W, drive force is min(max_drive_force, P / v)
    /// Arcade: top speed in reverse (m/s): the reverse drive force (a negative CarInputs::throttle)
    /// fades linearly from the full drive force at rest to none at this speed backwards;
    /// 0 gives the car no reverse. The vehicle model's reverse is its gearbox's instead.
    double max_reverse_speed = 10.0;
    double max_brake_force = 3.0e4;  ///< arcade: N over all wheels, bounded by grip
    /// Share of the brake force at the front wheels: more than half, so that the rear
    /// keeps its grip under braking and the car stays straight.
    double front_brake_share = 0.6;
    /// Both front wheels' angle at full steer (rad), at every speed and without Ackermann
    /// geometry: a game that wants less lock at speed scales CarInputs::steer itself, as the
    /// autopilot does through its steering law.
    double max_steer_angle = 0.6;
    /// A contact deeper than this share of the ellipsoid's half-extent along the contact
    /// normal, still approaching, is stopped by an impulse (see Car::advance).
    /// Half of a wheel's radius is 17 cm, twice its compression under 5 g of cornering.
    double deep_contact_fraction = 0.5;
    double drag_area = 0.35;      ///< C_d A (m^2): drag 1/2 rho C_d A v^2
    double downforce_area = 0.9;  ///< C_l A (m^2): downforce 1/2 rho C_l A v^2
    double air_density = 1.2;     ///< kg/m^3
    /// Spinning wheels, Magic Formula tyres and a drivetrain (docs/vehicle.md) in place of
    /// the arcade wheel forces; empty for the arcade car.
    std::optional<VehicleSpec> vehicle;

    /// A 1200 kg car, 4.5 m long and 2 m wide: four wheels (0.35 m radius, 0.15 m half
    /// width) and four body ellipsoids, tyres of 0.74 cm static sag, damping near
    /// critical, enough power and downforce to reach 1000 km/h.
    static CarSpec default_car();

    /// The names preset() knows: "arcade" (default_car()), "gt" and "formula".
    static std::span<const std::string_view> preset_names();
    /// The preset of that name (docs/vehicle.md#presets). Throws trackphys::Error naming
    /// the known presets for any other name.
    static CarSpec preset(std::string_view name);

    /// How far the car's lowest point (at full suspension droop) sits below its centre of
    /// mass when the car stands upright (m): the height at which to place the centre of
    /// mass for the wheels to touch flat ground.
    double lowest_point_depth() const;

    /// Empty when every field is in range; otherwise the first problem, naming the field
    /// (e.g. "CarSpec.ellipsoids[2].semi_axes.y must be finite and > 0, got 0").
    std::string validate() const;
};

}  // namespace trackphys
