#include "trackphys/vehicle/vehicle.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "trackphys/dynamics/car_spec.hpp"
#include "trackphys/error.hpp"
#include "vehicle/rolling_radius.hpp"

namespace trackphys {
namespace {

// A slip beyond this is a wheel spinning or sliding far past any curve's peak; the bound
// keeps a wheel spinning at standstill (|V_x| = 0, no relaxation) finite.
constexpr double kMaxSlip = 50.0;
// The slip ratio's range, MF 5.2's default KPUMIN / KPUMAX: the curves are fitted up to
// a wheel locked (-1) or spinning a little faster than that forwards, and a wheel spinning
// at standstill has no measured force beyond the sliding one they reach there.
constexpr double kMaxSlipRatio = 1.5;
// Rolling resistance grows from none at standstill to its full c_rr F_z at this rolling
// speed (m/s): a parked car feels none, so it does not creep on the tyres' jitter.
constexpr double kRollingResistanceFade = 0.5;

}  // namespace

Vehicle::Vehicle(const CarSpec& spec)
    : spec_(*spec.vehicle),
      front_tyre_(spec_.front_tyre),
      rear_tyre_(spec_.rear_tyre),
      front_drive_share_(spec.front_drive_share),
      slot_of_ellipsoid_(spec.ellipsoids.size(), -1) {
    for (std::size_t i = 0; i < spec.ellipsoids.size(); ++i) {
        const CarEllipsoid& e = spec.ellipsoids[i];
        if (e.role == EllipsoidRole::body) continue;
        Wheel wheel;
        wheel.ellipsoid = i;
        wheel.front = e.role == EllipsoidRole::front_wheel;
        wheel.radius = detail::rolling_radius(e);
        wheel.inverse_inertia = 1.0 / spec_.wheel_inertia;
        wheel.anti_roll = wheel.front ? spec_.front_anti_roll : spec_.rear_anti_roll;
        const TyreSpec& tyre = wheel.front ? spec_.front_tyre : spec_.rear_tyre;
        wheel.longitudinal_relaxation_rate = 1.0 / tyre.longitudinal_relaxation;
        wheel.lateral_relaxation_rate = 1.0 / tyre.lateral_relaxation;
        wheel.partner = i;
        for (std::size_t j = 0; j < spec.ellipsoids.size(); ++j)
            if (j != i && spec.ellipsoids[j].role == e.role &&
                (spec.ellipsoids[j].center.x > 0.0) != (e.center.x > 0.0))
                wheel.partner = j;
        slot_of_ellipsoid_[i] = static_cast<int>(wheels_.size());
        wheels_.push_back(wheel);
    }
    for (std::size_t w = 0; w < wheels_.size(); ++w) {
        Axle& axle = axles_[wheels_[w].front ? 0 : 1];
        if (axle.wheels < 2) axle.pair[axle.wheels] = w;
        ++axle.wheels;
    }
    const double front_share = axles_[1].wheels == 0   ? 1.0
                               : axles_[0].wheels == 0 ? 0.0
                                                       : spec.front_drive_share;
    for (Wheel& wheel : wheels_) {
        wheel.critical_mass = spec.mass.mass / static_cast<double>(wheels_.size());
        wheel.drive_share =
            wheel.front ? front_share / axles_[0].wheels : (1.0 - front_share) / axles_[1].wheels;
        drive_shares_squared_ += wheel.drive_share * wheel.drive_share;
        const double bias = wheel.front ? spec.front_brake_share : 1.0 - spec.front_brake_share;
        wheel.brake_share = spec_.max_brake_torque * bias / axles_[wheel.front ? 0 : 1].wheels;
    }
    state_.wheels.resize(wheels_.size());
    telemetry_.resize(wheels_.size());
}

void Vehicle::set_road_grip(std::size_t w, double grip) {
    if (w >= wheels_.size())
        throw Error("set_road_grip: wheel slot " + std::to_string(w) + " of " +
                    std::to_string(wheels_.size()));
    if (!(std::isfinite(grip) && grip > 0.0))
        throw Error("set_road_grip: wheel slot " + std::to_string(w) + ": grip " +
                    exact_text(grip) + " is not finite and above 0");
    wheels_[w].road_grip = grip;
}

void Vehicle::set_state(const VehicleState& state) {
    check_state(state);
    state_ = state;
}

void Vehicle::check_state(const VehicleState& state) const {
    const auto reject = [](const std::string& why) { throw Error("vehicle state: " + why); };
    if (state.wheels.size() != wheels_.size())
        reject(std::to_string(state.wheels.size()) + " wheels for " +
               std::to_string(wheels_.size()));
    for (std::size_t w = 0; w < state.wheels.size(); ++w) {
        const WheelState& s = state.wheels[w];
        if (!(std::isfinite(s.spin) && std::isfinite(s.road_torque) &&
              std::abs(s.slip_ratio) <= kMaxSlip && std::abs(s.lateral_slip) <= kMaxSlip))
            reject("wheel " + std::to_string(w) + " is not finite or its slip exceeds " +
                   exact_text(kMaxSlip));
    }
    const int gears = static_cast<int>(spec_.gearbox.ratios.size());
    if (!((state.gear >= 1 && state.gear <= gears) || state.gear == VehicleState::reverse_gear))
        reject("gear " + std::to_string(state.gear) + " is not in 1.." + std::to_string(gears) +
               " nor reverse (" + std::to_string(VehicleState::reverse_gear) + ")");
    if (!(state.shift_time_left >= 0.0 && state.shift_time_left <= spec_.gearbox.shift_time))
        reject("shift_time_left is not in [0, gearbox.shift_time]");
    if (!(state.clutch >= 0.0 && state.clutch <= 1.0)) reject("clutch is not in [0, 1]");
}

namespace {

// The brake takes a spin towards zero by step (rad/s) and holds it there when strong
// enough, so that a braked wheel does not chatter around standstill.
double braked(double spin, double step) {
    return std::abs(spin) <= step ? 0.0 : spin - std::copysign(step, spin);
}

}  // namespace

// Per sub-step: the tyre force from the slips the wheel carries, the spin under drive,
// tyre and brake torques, then the slips relaxed towards the new spin (implicitly: they
// are stiff). The force lies inside the friction ellipse by construction (Tyre::force),
// so above low_speed the spin follows from it explicitly; below, slow_wheel_force adds
// the tyre's damping.
TyreForce Vehicle::wheel_force(std::size_t w, double load, double rolling_velocity,
                               double lateral_velocity, double h, double surface_grip) {
    Wheel& wheel = wheels_[w];
    const double grip = wheel.road_grip * surface_grip;
    WheelState& s = state_.wheels[w];
    const double r = wheel.radius;
    const double speed = std::abs(rolling_velocity);
    TyreForce force;
    if (load > 0.0 && speed < spec_.low_speed) {
        force = slow_wheel_force(wheel, s, load, grip, rolling_velocity, lateral_velocity, h);
    } else {
        if (load > 0.0) force = tyre_of(wheel).force(wheel.slip, tyre_of(wheel).peaks(load, grip));
        const double drive = load > 0.0 ? wheel.drive_torque : wheel.airborne_drive_torque;
        const double torque = drive - r * force.longitudinal;
        s.spin = braked(s.spin + h * wheel.inverse_inertia * torque,
                        h * wheel.inverse_inertia * wheel.brake_torque);
    }
    s.road_torque = 0.0;
    if (load > 0.0) {
        s.road_torque = -r * force.longitudinal;
        // sigma dk/dt + |V_x| k = w R - V_x, implicit Euler. Past its peak slip the contact
        // patch slides: the carcass keeps the peak's deflection sigma k_peak and no more, so
        // the relaxation length shrinks to sigma k_peak / |k| (the slip normalised by its
        // peak, from the start of the sub-step). A slip built by a wheel that spun in the air
        // or at standstill then follows the wheel at once, instead of at |V_x| / sigma, which
        // is walking pace after a landing (docs/vehicle.md, "Relaxation length").
        const double rate_x = h * wheel.longitudinal_relaxation_rate *
                              std::max(1.0, std::abs(wheel.slip.longitudinal));
        const double rate_y =
            h * wheel.lateral_relaxation_rate * std::max(1.0, std::abs(wheel.slip.lateral));
        s.slip_ratio = std::clamp(
            (s.slip_ratio + rate_x * (s.spin * r - rolling_velocity)) / (1.0 + rate_x * speed),
            -kMaxSlipRatio, kMaxSlipRatio);
        s.lateral_slip =
            std::clamp((s.lateral_slip - rate_y * lateral_velocity) / (1.0 + rate_y * speed),
                       -kMaxSlip, kMaxSlip);
    }
    // In the air the slips keep their values: a wheel skipping over a kink between road
    // facets for a few sub-steps lands with the deflection it left with, instead of
    // building its force up again over a relaxation length at every skip.
    telemetry_[w] = {s.slip_ratio, s.lateral_slip, load, s.spin};
    // Rolling resistance, c_rr F_z against the rolling direction: the carcass's hysteresis,
    // which holds the car back at the contact without turning the wheel.
    force.longitudinal -= spec_.rolling_resistance * load *
                          std::clamp(rolling_velocity / kRollingResistanceFade, -1.0, 1.0);
    return force;
}

// Below low_speed the tyre also damps its own deflection (Pacejka 2012, sec. 7.2.4),
// fading out linearly with the contact's speed over the road, at the critical damping of
// the deflection spring C / sigma under the wheel's share of the car's mass; the whole
// force, damping included, stays in the friction ellipse, and within the curve's force
// once the tyre slides. The spin is implicit in the damping, then braked.
TyreForce Vehicle::slow_wheel_force(const Wheel& wheel, WheelState& s, double load, double grip,
                                    double rolling_velocity, double lateral_velocity, double h) {
    const Tyre& tyre = tyre_of(wheel);
    const TyreSpec& ts = tyre.spec();
    const double r = wheel.radius;

    // The dry road's peaks, and the friction ellipse that bounds the total force, damping
    // included (N for each direction).
    const TyreForce dry = tyre.peaks(load);
    const double dx = grip * dry.longitudinal;
    const double dy = grip * dry.lateral;
    const TyreForce force = tyre.force(wheel.slip, TyreForce{dx, dy});
    // The fade reads the contact's whole speed, not the rolling speed alone: a wheel sliding
    // sideways faster than low_speed gets the curve's sliding force, as it does once it
    // rolls faster than low_speed, not the damper's push to the ellipse's edge (up to 23%
    // more, with a jump at low_speed).
    const double fade =
        std::max(0.0, 1.0 - std::hypot(rolling_velocity, lateral_velocity) / spec_.low_speed);
    const double slope_x = ts.longitudinal.slip_stiffness(dry.longitudinal);
    const double slope_y = ts.lateral.slip_stiffness(dry.lateral);
    const double damping_x =
        fade * 2.0 * std::sqrt(slope_x / ts.longitudinal_relaxation * wheel.critical_mass);
    const double damping_y =
        fade * 2.0 * std::sqrt(slope_y / ts.lateral_relaxation * wheel.critical_mass);

    // The share of the friction ellipse a force uses (1 at its edge).
    const auto share = [&](const TyreForce& f) {
        const double ux = f.longitudinal / dx;
        const double uy = f.lateral / dy;
        return std::sqrt(ux * ux + uy * uy);
    };
    // How much of the ellipse the damper may fill: all of it while the tyre grips, the
    // curve's own share F(s) / D once it slides past its peak slip (s > 1), so that a slow
    // slide grips as the curve says, not at the ellipse's edge. The two meet at s = 1.
    const double limit = wheel.slip.combined > 1.0 ? share(force) : 1.0;
    const auto damped = [&](double spin) {
        TyreForce total{force.longitudinal - damping_x * (rolling_velocity - spin * r),
                        force.lateral - damping_y * lateral_velocity};
        const double used = share(total);
        if (used > limit)
            total.longitudinal = total.longitudinal / used * limit,
            total.lateral = total.lateral / used * limit;
        return std::pair(total, used > limit);
    };

    // I dw/dt = T_drive - R (F_x - c_x (V_x - w R)), implicit in the damping. When that
    // force passes its limit (the ellipse, or the curve's share for a sliding tyre) the road
    // holds the wheel only with the bounded force, explicitly. Then the brake.
    const double step = h * wheel.inverse_inertia;
    double stiff = 1.0 + step * damping_x * r * r;
    double spin = (s.spin + step * (wheel.drive_torque - r * force.longitudinal +
                                    damping_x * r * rolling_velocity)) /
                  stiff;
    auto [total, sliding] = damped(spin);
    if (sliding) {
        spin = s.spin + step * (wheel.drive_torque - r * total.longitudinal);
        stiff = 1.0;
    }
    s.spin = braked(spin, step * wheel.brake_torque / stiff);
    return sliding ? total : damped(s.spin).first;
}

void Vehicle::measure_anti_roll(std::span<const double> suspension) {
    for (Wheel& wheel : wheels_)
        wheel.anti_roll_force =
            wheel.anti_roll * (suspension[wheel.ellipsoid] - suspension[wheel.partner]);
}

}  // namespace trackphys
