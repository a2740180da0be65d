// The drivetrain half of Vehicle: shifter, clutch, engine, differentials and brakes turn
// the driver's throttle and brake into each wheel's drive and brake torque.

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "trackphys/dynamics/car_spec.hpp"
#include "trackphys/vehicle/vehicle.hpp"

namespace trackphys {
namespace {

constexpr double kRpmPerRadPerSecond = 60.0 / (2.0 * std::numbers::pi);

// How much of its torque anti-lock or traction control leaves a wheel whose tyre works at
// combined slip s (Tyre::force's normalised slip, 1 at the friction ellipse): all up to
// s = 0.9, none beyond 1.2, where the curve is within a few per cent of its peak. The
// combined slip, not the slip ratio alone: a tyre turning at its peak slip angle has no
// grip left to drive or brake with, and a wheel driven or braked to its longitudinal peak
// in a turn loses its lateral force (a rear-driven car spins out of the turn).
double slip_limiter(double combined_slip) {
    if (combined_slip <= 0.9) return 1.0;  // most sub-steps: no division
    return std::clamp((1.2 - combined_slip) / 0.3, 0.0, 1.0);
}

// A limited-slip clutch between two outputs turning at speeds a and b (rad/s): the torque
// it moves from the faster to the slower, at most capacity. It is a stiff viscous
// coupling bounded by the capacity; the gain, a quarter of what would stop the speed
// difference in one step of h seconds, keeps the explicit sub-step stable.
double limited_slip_transfer(double a, double b, double capacity, double inertia, double h) {
    const double gain = 0.25 * inertia / h;
    return std::clamp(gain * (a - b), -capacity, capacity);
}

}  // namespace

// A teleported car in the gear the shifter would have reached under throttle.
VehicleState Vehicle::rolling_at(double speed) const {
    VehicleState rolling;
    for (const Wheel& wheel : wheels_) rolling.wheels.push_back({.spin = speed / wheel.radius});
    if (speed <= -CarSpec::reverse_engage_speed) {
        rolling.gear = VehicleState::reverse_gear;
        return rolling;
    }
    const GearboxSpec& box = spec_.gearbox;
    const int top = static_cast<int>(box.ratios.size());
    // The driven wheels' mean spin, as the gearbox sees it (drive shares sum to 1).
    double driven_spin = 0.0;
    for (std::size_t w = 0; w < wheels_.size(); ++w)
        driven_spin += wheels_[w].drive_share * rolling.wheels[w].spin;
    const auto rpm_in = [&](int gear) {
        return driven_spin * box.ratios[static_cast<std::size_t>(gear - 1)] * box.final_drive *
               kRpmPerRadPerSecond;
    };
    while (rolling.gear < top && rpm_in(rolling.gear) > box.shift_up_rpm) ++rolling.gear;
    return rolling;
}

double Vehicle::engine_torque(double rpm, double throttle) const {
    const EngineSpec& engine = spec_.engine;
    if (rpm > engine.redline_rpm) return -engine.friction_torque;  // the limiter cuts fuel
    const std::vector<TorquePoint>& curve = engine.torque_curve;
    double full = curve.front().torque;  // below the first point
    if (rpm >= curve.back().rpm) {
        full = curve.back().torque;
    } else if (rpm >= curve.front().rpm) {
        // The points ascend: rpm's segment ends at the first point above it.
        const auto above =
            std::upper_bound(curve.begin(), curve.end(), rpm,
                             [](double x, const TorquePoint& point) { return x < point.rpm; });
        const TorquePoint& from = *(above - 1);
        const double t = (rpm - from.rpm) / (above->rpm - from.rpm);
        full = from.torque + t * (above->torque - from.torque);
    }
    const double friction = engine.friction_torque * std::max(rpm, 0.0) / engine.redline_rpm;
    return throttle * full - (1.0 - throttle) * friction;
}

double Vehicle::ground_rpm(int gear, double forward_speed) const {
    const GearboxSpec& box = spec_.gearbox;
    double driven_radius = 0.0;  // drive shares sum to 1
    for (const Wheel& wheel : wheels_) driven_radius += wheel.drive_share * wheel.radius;
    return forward_speed / driven_radius * box.ratios[static_cast<std::size_t>(gear - 1)] *
           box.final_drive * kRpmPerRadPerSecond;
}

double Vehicle::gear_ratio() const {
    const GearboxSpec& box = spec_.gearbox;
    return state_.gear == VehicleState::reverse_gear
               ? -box.reverse_ratio
               : box.ratios[static_cast<std::size_t>(state_.gear - 1)];
}

// Into reverse under a negative throttle once the wheels and the body move forwards slower
// than CarSpec::reverse_engage_speed, and back into first under a positive one once they
// move backwards slower than that; otherwise up a gear above shift_up_rpm under throttle, down
// below shift_down_rpm (never in reverse, which has one gear). A change opens the clutch
// for shift_time, then it closes over clutch_engage_time.
//
// Up only when the car's own speed would keep the engine above shift_down_rpm in the next
// gear: driven wheels spinning on the spot read as engine speed the car does not have, and
// a box that shifted on them alone went up, lost the spin during the shift and came down
// again (1-2-1-2 in 2.6 s of a launch without traction control). The engine then meets its
// limiter in the lower gear, as a real one does. In a clean upshift the next gear's rpm is
// shift_up_rpm times the ratios' quotient, above shift_down_rpm, so the test does not bite.
// Without throttle, up only when the car's speed drives the engine past its redline.
//
// Down only when the car's own speed would keep the engine at or below shift_up_rpm in the
// gear below, for the same reason the other way: braked wheels, locked or stopped in the
// air, read as a speed the car has not lost, and a box that shifted on them alone went
// down to first and, once they rolled again, dragged the engine far past its redline.
void Vehicle::shift_gears(double drivetrain_rpm, double throttle, double rolling_speed,
                          double forward_speed, double h) {
    const GearboxSpec& box = spec_.gearbox;
    if (state_.shift_time_left > 0.0) {
        state_.shift_time_left = std::max(0.0, state_.shift_time_left - h);
        state_.clutch = 0.0;
        return;
    }
    state_.clutch = std::min(1.0, state_.clutch + h / box.clutch_engage_time);
    if (state_.clutch < 1.0) return;
    const int top = static_cast<int>(box.ratios.size());
    constexpr int reverse = VehicleState::reverse_gear;
    int gear = state_.gear;
    // Wheels and body both nearly stopped or moving the new way: locked wheels on a car
    // still sliding forwards read as stopped.
    constexpr double engage = CarSpec::reverse_engage_speed;
    if (throttle < 0.0 && gear != reverse && rolling_speed < engage && forward_speed < engage)
        gear = reverse;
    else if (throttle > 0.0 && gear == reverse && rolling_speed > -engage &&
             forward_speed > -engage)
        gear = 1;
    else if (gear == reverse)
        return;
    else if (drivetrain_rpm > box.shift_up_rpm && gear < top &&
             (throttle > 0.0 ? ground_rpm(gear + 1, forward_speed) >= box.shift_down_rpm
                             : ground_rpm(gear, forward_speed) > spec_.engine.redline_rpm))
        ++gear;
    else if (drivetrain_rpm < box.shift_down_rpm && gear > 1 &&
             ground_rpm(gear - 1, forward_speed) <= box.shift_up_rpm)
        --gear;
    if (gear == state_.gear) return;
    state_.gear = gear;
    state_.shift_time_left = box.shift_time;
    state_.clutch = 0.0;
}

// The torque the gearbox passes to the differentials when the clutch locks engine and
// wheels together. Each driven wheel k takes the share f_k of it (the open differentials'
// split) and the engine turns at G sum f_k w_k, so with the wheels' road torques tau_k
// I_w a_k = f_k T + tau_k and I_e a_e = T_e - T / G give
//     T = G (T_e - I_e G sum f_k tau_k / I_w) / (1 + I_e G^2 sum f_k^2 / I_w):
// the engine's inertia takes its part of the torque, so a wheel on ice spins the engine up
// instead of passing the full torque to the wheel across the differential. The road
// torques are the last sub-step's.
double Vehicle::gearbox_torque(double engine_torque, double gear_ratio) const {
    double shared_road_torque = 0.0;
    for (std::size_t w = 0; w < wheels_.size(); ++w)
        shared_road_torque += wheels_[w].drive_share * state_.wheels[w].road_torque;
    const double coupling = state_.clutch * spec_.engine.inertia * gear_ratio / spec_.wheel_inertia;
    return state_.clutch * gear_ratio * (engine_torque - coupling * shared_road_torque) /
           (1.0 + coupling * gear_ratio * drive_shares_squared_);
}

void Vehicle::begin_substep(double throttle, double brake, double car_speed, double forward_speed,
                            double h) {
    // The gearbox output turns at sum f_k w_k (the differentials average their outputs).
    double driven_spin = 0.0;
    double axle_spin[2] = {0.0, 0.0};  // front, rear
    double rolling_speed = 0.0;        // the wheels' mean, as the shifter sees the car move
    for (std::size_t w = 0; w < wheels_.size(); ++w) {
        driven_spin += wheels_[w].drive_share * state_.wheels[w].spin;
        axle_spin[wheels_[w].front ? 0 : 1] += state_.wheels[w].spin;
        rolling_speed += state_.wheels[w].spin * wheels_[w].radius;
    }
    for (int axle : {0, 1}) axle_spin[axle] /= std::max(axles_[axle].wheels, 1);
    rolling_speed /= static_cast<double>(std::max<std::size_t>(wheels_.size(), 1));

    const GearboxSpec& box = spec_.gearbox;
    shift_gears(driven_spin * gear_ratio() * box.final_drive * kRpmPerRadPerSecond, throttle,
                rolling_speed, forward_speed, h);
    // In reverse the ratio is negative: the engine turns forwards (rpm > 0) while the wheels
    // turn backwards, and its torque drives them backwards.
    const double overall_ratio = gear_ratio() * box.final_drive;
    const double rpm = driven_spin * overall_ratio * kRpmPerRadPerSecond;
    // The pedal the engine sees: the throttle's size in the gear's direction, closed when
    // the driver asks for the other direction before the shifter could engage it.
    const bool reversing = state_.gear == VehicleState::reverse_gear;
    const double pedal = reversing ? std::max(-throttle, 0.0) : std::max(throttle, 0.0);
    const double direction = reversing ? -1.0 : 1.0;         // of the drive, along the wheels' spin
    const double moving = forward_speed < 0.0 ? -1.0 : 1.0;  // of the car along its heading

    // Above launch_rpm the closed clutch locks engine and wheels together. Below it the
    // clutch slips with the engine held at launch_rpm, passing that speed's torque under
    // the pedal and, as the pedal closes, the engine's drag at the drivetrain's speed
    // (proportional to it, so none at standstill: a parked car does not creep).
    const bool locked = rpm >= box.launch_rpm;
    engine_rpm_ = locked ? rpm : (pedal > 0.0 ? box.launch_rpm : spec_.engine.idle_rpm);
    const double torque = locked ? gearbox_torque(engine_torque(rpm, pedal), overall_ratio)
                                 : state_.clutch * overall_ratio *
                                       (pedal * engine_torque(box.launch_rpm, 1.0) +
                                        (1.0 - pedal) * engine_torque(rpm, 0.0));
    for (Wheel& wheel : wheels_) wheel.drive_torque = wheel.drive_share * torque;

    // The limited-slip clutches move torque from the faster output to the slower.
    const double front_share = front_drive_share_;
    if (front_share > 0.0 && front_share < 1.0 &&
        spec_.centre_differential.kind == DifferentialKind::limited_slip) {
        const double transfer =
            limited_slip_transfer(axle_spin[0], axle_spin[1],
                                  spec_.centre_differential.preload +
                                      spec_.centre_differential.locking * std::abs(torque),
                                  2.0 * spec_.wheel_inertia, h);
        for (Wheel& wheel : wheels_)
            wheel.drive_torque += (wheel.front ? -transfer : transfer) /
                                  std::max(axles_[wheel.front ? 0 : 1].wheels, 1);
    }
    if (front_share > 0.0) lock_axle(true, front_share * torque, h);
    if (front_share < 1.0) lock_axle(false, (1.0 - front_share) * torque, h);

    for (std::size_t w = 0; w < wheels_.size(); ++w) {
        Wheel& wheel = wheels_[w];
        const double slip = state_.wheels[w].slip_ratio;
        wheel.slip = tyre_of(wheel).normalised(slip, state_.wheels[w].lateral_slip);
        // In the air the tyre has no slip to read: traction control compares the wheel's
        // speed with the car's instead, as real systems compare the driven wheels with the
        // undriven ones, so that a wheel held at full throttle does not spin up before it
        // lands (the slip ratio of that speed difference, over at least low_speed).
        // Driving and braking are read along the drive's direction: in reverse a driven
        // wheel spins backwards (slip < 0) and a braked one is held back (slip > 0).
        wheel.airborne_drive_torque = wheel.drive_torque;
        if (spec_.traction_control && direction * wheel.drive_torque > 0.0) {
            const double airborne_slip =
                (direction * state_.wheels[w].spin * wheel.radius - car_speed) /
                std::max(car_speed, spec_.low_speed);
            wheel.airborne_drive_torque *=
                slip_limiter(airborne_slip / tyre_of(wheel).peak_slip_ratio());
        }
        if (spec_.traction_control && direction * wheel.drive_torque > 0.0 &&
            direction * slip > 0.0)
            wheel.drive_torque *= slip_limiter(wheel.slip.combined);
        wheel.brake_torque = brake * wheel.brake_share;
        // Anti-lock acts above walking pace only, as real systems do: at rest the brake
        // must hold the car however the tyres deflect. A braked wheel turns slower than
        // the road moves, whichever way the car goes and whatever the gear.
        if (spec_.anti_lock && car_speed > 1.0 && moving * slip < 0.0)
            wheel.brake_torque *= slip_limiter(wheel.slip.combined);
    }
}

// A limited-slip axle differential with two wheels: its clutch's transfer between them.
void Vehicle::lock_axle(bool front, double torque, double h) {
    const DifferentialSpec& diff = front ? spec_.front_differential : spec_.rear_differential;
    const Axle& axle = axles_[front ? 0 : 1];
    if (diff.kind != DifferentialKind::limited_slip || axle.wheels != 2) return;
    const std::array<std::size_t, 2>& pair = axle.pair;
    const double transfer = limited_slip_transfer(
        state_.wheels[pair[0]].spin, state_.wheels[pair[1]].spin,
        diff.preload + diff.locking * std::abs(torque), spec_.wheel_inertia, h);
    wheels_[pair[0]].drive_torque -= transfer;
    wheels_[pair[1]].drive_torque += transfer;
}

}  // namespace trackphys
