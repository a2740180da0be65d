#pragma once

#include <array>
#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include "trackphys/export.hpp"
#include "trackphys/vehicle/tyre.hpp"
#include "trackphys/vehicle/vehicle_spec.hpp"

namespace trackphys {

struct CarSpec;

namespace detail {
struct VehicleAccess;  // src/vehicle/vehicle_access.hpp: Car's sub-step of its model
}  // namespace detail

/// One wheel's state: what the next sub-step reads.
struct WheelState {
    double spin = 0.0;  ///< rad/s about its axle, > 0 rolling forward
    /// The tyre's transient slips (docs/vehicle.md#tyre-the-magic-formula): slip ratio
    /// kappa' and lateral slip tan(alpha)', relaxed towards their steady-state values.
    double slip_ratio = 0.0;
    double lateral_slip = 0.0;
    /// N m the road put on the wheel in the last sub-step (the gearbox torque reads it).
    double road_torque = 0.0;

    bool operator==(const WheelState&) const = default;
};

/// Everything of a Vehicle that a later sub-step reads: its part of a car's snapshot.
struct VehicleState {
    /// The gear value of reverse (GearboxSpec::reverse_ratio).
    static constexpr int reverse_gear = -1;

    std::vector<WheelState> wheels;  ///< in CarSpec ellipsoid order, wheels only
    int gear = 1;                    ///< 1 = first .. the top gear; reverse_gear in reverse
    double shift_time_left = 0.0;    ///< s until the gear change completes
    double clutch = 1.0;             ///< engagement, 0 open .. 1 closed

    bool operator==(const VehicleState&) const = default;
};

/// What a wheel did in the last sub-step, for telemetry.
struct WheelTelemetry {
    double slip_ratio = 0.0;    ///< kappa'
    double lateral_slip = 0.0;  ///< tan(alpha)': the slip angle is its atan, > 0 pushes left
    double load = 0.0;          ///< N, the tyre's normal force
    double spin = 0.0;          ///< rad/s
};

/// The vehicle model of a car whose CarSpec has a `vehicle` (docs/vehicle.md): the wheels'
/// spin, the tyres' transient slips and forces, and the drivetrain (engine, clutch,
/// automatic gearbox, differentials, brakes with anti-lock and traction control). Car
/// drives it once per sub-step: begin_substep(), then wheel_force() for every wheel. Those
/// steps are private, reached through detail::VehicleAccess (src/vehicle/vehicle_access.hpp)
/// by Car and the tests: a game holds a World's car's model through Car::vehicle() to read
/// its telemetry and set its road grip, and a sub-step run from there would leave the car
/// behind.
class TRACKPHYS_API Vehicle {
  public:
    /// spec must hold a vehicle (CarSpec::validate() has checked it).
    explicit Vehicle(const CarSpec& spec);

    const VehicleState& state() const { return state_; }
    /// Replaces the state. Throws trackphys::Error naming the field when it does not fit
    /// this vehicle (wheel count, gear range) or is not finite.
    void set_state(const VehicleState& state);
    /// Throws what set_state() would throw for `state`, changing nothing.
    void check_state(const VehicleState& state) const;

    /// This vehicle's state at rest: wheels still, first gear, clutch closed (a reset).
    VehicleState at_rest() const { return rolling_at(0.0); }
    /// This vehicle's state rolling at speed (m/s, along its heading) as if it had driven
    /// so (a teleport): every wheel spinning at speed / R without slip, no road torque, the
    /// lowest gear whose engine speed is at most shift_up_rpm (reverse at or below
    /// -CarSpec::reverse_engage_speed, where the shifter keeps a reversing car), the clutch
    /// closed.
    VehicleState rolling_at(double speed) const;

    /// The wheel slot of ellipsoid i (-1 for a body ellipsoid).
    int wheel_slot(std::size_t ellipsoid) const { return slot_of_ellipsoid_[ellipsoid]; }

    /// The grip of the road under wheel slot w relative to a dry road (1 by default; 0.05
    /// for ice): scales its tyre's peaks. Part of the environment, not of the state (a
    /// snapshot does not carry it). Throws trackphys::Error for a slot past the wheels or a
    /// grip that is not finite and above 0 (a negative one would push the tyre along its
    /// slip, adding energy; zero would leave its force 0 / 0).
    void set_road_grip(std::size_t w, double grip);

    /// The anti-roll bar's force on wheel slot w's suspension (N, resisting compression).
    double anti_roll_force(std::size_t w) const { return wheels_[w].anti_roll_force; }

    /// The last sub-step's engine speed (rev/min) and each wheel's telemetry.
    double engine_rpm() const { return engine_rpm_; }
    std::span<const WheelTelemetry> telemetry() const { return telemetry_; }

  private:
    friend struct detail::VehicleAccess;

    /// The drivetrain's share of a sub-step of h seconds: the shifter, the clutch, the
    /// engine's torque through the gearbox and differentials, and the brakes, at throttle
    /// in -1..1 (< 0 asks for reverse, CarInputs), brake in 0..1, the car's speed (m/s) and
    /// its velocity along its heading (m/s, < 0 backwards), into each wheel's torques.
    void begin_substep(double throttle, double brake, double car_speed, double forward_speed,
                       double h);

    /// The tyre force in its contact frame (N) of wheel slot w under load (N, 0 when in
    /// the air) with the contact point moving at rolling_velocity along the wheel's
    /// heading and lateral_velocity across it (m/s, in the contact plane), on a surface of
    /// grip surface_grip (Surface::grip, finite and > 0: it scales the tyre's peaks on top of
    /// set_road_grip); advances the wheel's spin and slips by h seconds.
    TyreForce wheel_force(std::size_t w, double load, double rolling_velocity,
                          double lateral_velocity, double h, double surface_grip = 1.0);

    /// Sets every wheel's anti-roll bar force from the suspension compression of every
    /// ellipsoid (m), all at once so that no wheel sees its partner's already updated.
    void measure_anti_roll(std::span<const double> suspension);

    struct Wheel {
        std::size_t ellipsoid = 0;
        bool front = false;
        double radius = 0.3;
        double inverse_inertia = 1.0;               // 1 / kg m^2
        double longitudinal_relaxation_rate = 1.0;  // 1 / sigma_x, 1/m
        double lateral_relaxation_rate = 1.0;       // 1 / sigma_y, 1/m
        double anti_roll = 0.0;                     // N/m against the partner's travel
        double anti_roll_force = 0.0;               // N, from measure_anti_roll
        double road_grip = 1.0;
        std::size_t partner = 0;     // ellipsoid across the axle (itself if none)
        double critical_mass = 0.0;  // kg: the car's mass share for low-speed damping
        double drive_share = 0.0;    // of the gearbox's torque, through the differentials
        double brake_share = 0.0;    // N m at full brake
        // This sub-step's: the slips the wheel carries, normalised (the drivetrain's
        // anti-lock and traction control and the tyre force read them), and the
        // drivetrain's output.
        NormalisedSlip slip;
        double drive_torque = 0.0;
        double airborne_drive_torque = 0.0;  // the drive when the wheel carries no load
        double brake_torque = 0.0;
    };
    struct Axle {
        int wheels = 0;
        std::array<std::size_t, 2> pair{};  // its wheel slots, when it has two
    };

    /// grip: the wheel's road_grip times the surface's.
    TyreForce slow_wheel_force(const Wheel& wheel, WheelState& s, double load, double grip,
                               double rolling_velocity, double lateral_velocity, double h);
    /// rolling_speed: the wheels' mean rolling speed; forward_speed: the body's along its
    /// heading (m/s, < 0 backwards).
    void shift_gears(double drivetrain_rpm, double throttle, double rolling_speed,
                     double forward_speed, double h);
    /// The engine's rpm in forward gear `gear` were the driven wheels rolling at the car's
    /// forward speed (m/s), without slip.
    double ground_rpm(int gear, double forward_speed) const;
    /// The current gear's ratio, negative in reverse (without the final drive).
    double gear_ratio() const;
    double engine_torque(double rpm, double throttle) const;
    double gearbox_torque(double engine_torque, double gear_ratio) const;
    void lock_axle(bool front, double torque, double h);
    const Tyre& tyre_of(const Wheel& wheel) const { return wheel.front ? front_tyre_ : rear_tyre_; }

    VehicleSpec spec_;
    Tyre front_tyre_;
    Tyre rear_tyre_;
    double front_drive_share_;
    std::vector<Wheel> wheels_;
    std::array<Axle, 2> axles_;          // front, rear
    double drive_shares_squared_ = 0.0;  // sum of the wheels' drive_share^2
    std::vector<int> slot_of_ellipsoid_;
    VehicleState state_;
    double engine_rpm_ = 0.0;
    std::vector<WheelTelemetry> telemetry_;
};

}  // namespace trackphys
