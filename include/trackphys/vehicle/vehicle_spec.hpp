#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "trackphys/export.hpp"
#include "trackphys/vehicle/tyre.hpp"

namespace trackphys {

/// One point of the engine's full-throttle torque curve.
struct TorquePoint {
    double rpm = 0.0;     ///< engine speed, rev/min
    double torque = 0.0;  ///< N m at full throttle
};

/// The engine: torque interpolated linearly between the curve's points (held flat beyond
/// its ends), cut above the redline.
struct EngineSpec {
    /// The most points a torque curve may have (a dyno run every 5 rpm to 20,000 rpm).
    static constexpr std::size_t max_torque_points = 4096;
    std::vector<TorquePoint> torque_curve;  ///< rpm strictly ascending, torque >= 0
    double idle_rpm = 1000.0;
    double redline_rpm = 7000.0;
    double inertia = 0.2;  ///< kg m^2, crankshaft and flywheel
    /// Engine braking at zero throttle, at the redline (N m; proportional to rpm below).
    double friction_torque = 50.0;
};

/// Gearbox, final drive, clutch and the automatic shifter.
struct GearboxSpec {
    std::vector<double> ratios;  ///< forward gears, first to top, each > 0
    double final_drive = 3.5;
    double shift_up_rpm = 6500.0;      ///< the shifter goes up a gear above this
    double shift_down_rpm = 3000.0;    ///< and down below this
    double shift_time = 0.1;           ///< s without drive while the gear changes
    double clutch_engage_time = 0.05;  ///< s for the clutch to close after a shift
    /// Below this drivetrain speed the clutch slips: the engine holds this speed and passes
    /// its torque at it under the pedal (a launch) and, as the pedal closes, its drag at the
    /// drivetrain's speed (engine braking that fades to none at standstill). In
    /// [engine.idle_rpm, shift_up_rpm].
    double launch_rpm = 3000.0;
    /// The reverse gear's ratio (> 0; it turns the wheels backwards). The shifter engages
    /// it under a negative throttle once the car is nearly stopped or rolling backwards
    /// (CarInputs), and first gear again under a positive one; it never shifts on rpm in
    /// reverse, so the redline bounds the speed backwards.
    double reverse_ratio = 3.5;
};

enum class DifferentialKind {
    open,          ///< equal torque to both outputs, whatever their speeds
    limited_slip,  ///< also moves up to preload + locking |T_in| from the faster output
};

struct DifferentialSpec {
    DifferentialKind kind = DifferentialKind::open;
    double preload = 0.0;  ///< N m the limited-slip clutch transfers at zero input torque
    double locking = 0.0;  ///< share of the input torque it may transfer, 0..1
};

/// A car with spinning wheels, Magic Formula tyres and a drivetrain (docs/vehicle.md),
/// on top of CarSpec's ellipsoids, mass, suspension and aerodynamics. CarSpec's
/// front_drive_share splits the torque at the centre differential (0 = rear drive) and
/// front_brake_share is the brake bias; the arcade drive and grip fields (rear_grip_factor,
/// max_drive_force, max_drive_power, traction_limit, max_brake_force, max_reverse_speed)
/// are not used.
struct VehicleSpec {
    std::string model = "gt";  ///< the preset it came from, for the spec file's "model"
    TyreSpec front_tyre;
    TyreSpec rear_tyre;
    double wheel_inertia = 1.0;  ///< kg m^2 per wheel about its axle
    EngineSpec engine;
    GearboxSpec gearbox;
    DifferentialSpec front_differential;
    DifferentialSpec rear_differential;
    DifferentialSpec centre_differential;  ///< between the axles (all-wheel drive only)
    double max_brake_torque = 8000.0;      ///< N m over all wheels at full brake
    /// Anti-lock brakes and traction control: a braked or driven wheel's torque fades out
    /// as its tyre's combined normalised slip (1 on the friction ellipse) goes from 0.9 to
    /// 1.2, so the tyre stays near its peak; anti-lock above 1 m/s only. In the air
    /// traction control reads the wheel's speed over the car's instead.
    bool anti_lock = true;
    bool traction_control = true;
    double front_anti_roll = 0.0;  ///< N/m per metre of travel difference across the axle
    double rear_anti_roll = 0.0;
    /// Below this speed the tyres add damping to their deflection (m/s), so that a car
    /// coming to rest does not rock on its tyres' springs.
    double low_speed = 3.0;
    /// Rolling resistance coefficient c_rr, in [0, 0.1]: each wheel on the road is held
    /// back by c_rr F_z against its rolling direction, faded in over the first 0.5 m/s of
    /// its contact's speed along the wheel's heading so that a car at rest does not creep.
    /// It adds to the tyre's force after the friction ellipse (a locked wheel sliding on
    /// a road of grip 1 is held back by (mu + c_rr) F_z).
    double rolling_resistance = 0.012;

    /// Empty when every field is in range; else the first problem, naming the field
    /// (e.g. "CarSpec.vehicle.gearbox.ratios[2] must be finite and > 0, got 0").
    TRACKPHYS_API std::string validate() const;
};

}  // namespace trackphys
