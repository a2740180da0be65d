#include "vehicle/vehicle_fingerprint.hpp"

namespace trackphys {
namespace {

// The size checks fail to compile when a field is added, as a reminder to hash it too.
static_assert(sizeof(VehicleSpec) == 504, "a new VehicleSpec field must join its fingerprint");
static_assert(sizeof(TyreSpec) == 104, "a new TyreSpec field must join the fingerprint");

void add(core::Fnv1a& hash, const MagicFormulaCurve& c) {
    hash.add(c.stiffness), hash.add(c.shape), hash.add(c.curvature), hash.add(c.friction),
        hash.add(c.friction_load_slope);
}

void add(core::Fnv1a& hash, const TyreSpec& t) {
    add(hash, t.longitudinal), add(hash, t.lateral);
    hash.add(t.nominal_load), hash.add(t.longitudinal_relaxation), hash.add(t.lateral_relaxation);
}

void add(core::Fnv1a& hash, const DifferentialSpec& d) {
    hash.add(static_cast<std::uint64_t>(d.kind)), hash.add(d.preload), hash.add(d.locking);
}

}  // namespace

std::uint64_t fingerprint(const VehicleSpec& v) {
    core::Fnv1a hash;
    hash.add(v.model.data(), v.model.size());
    add(hash, v.front_tyre), add(hash, v.rear_tyre);
    hash.add(v.wheel_inertia);
    hash.add(static_cast<std::uint64_t>(v.engine.torque_curve.size()));
    for (const TorquePoint& p : v.engine.torque_curve) hash.add(p.rpm), hash.add(p.torque);
    for (const double x :
         {v.engine.idle_rpm, v.engine.redline_rpm, v.engine.inertia, v.engine.friction_torque})
        hash.add(x);
    hash.add(static_cast<std::uint64_t>(v.gearbox.ratios.size()));
    for (const double ratio : v.gearbox.ratios) hash.add(ratio);
    for (const double x : {v.gearbox.final_drive, v.gearbox.shift_up_rpm, v.gearbox.shift_down_rpm,
                           v.gearbox.shift_time, v.gearbox.clutch_engage_time, v.gearbox.launch_rpm,
                           v.gearbox.reverse_ratio})
        hash.add(x);
    add(hash, v.front_differential), add(hash, v.rear_differential),
        add(hash, v.centre_differential);
    for (const double x : {v.max_brake_torque, v.front_anti_roll, v.rear_anti_roll, v.low_speed,
                           v.rolling_resistance})
        hash.add(x);
    hash.add(static_cast<std::uint64_t>(v.anti_lock)),
        hash.add(static_cast<std::uint64_t>(v.traction_control));
    return hash.value;
}

void add_to_hash(core::Fnv1a& hash, const VehicleState& state) {
    for (const WheelState& wheel : state.wheels)
        hash.add(wheel.spin), hash.add(wheel.slip_ratio), hash.add(wheel.lateral_slip),
            hash.add(wheel.road_torque);
    hash.add(static_cast<std::uint64_t>(state.gear));
    hash.add(state.shift_time_left), hash.add(state.clutch);
}

}  // namespace trackphys
