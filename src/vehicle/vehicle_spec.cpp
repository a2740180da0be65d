#include "trackphys/vehicle/vehicle_spec.hpp"

#include <cmath>
#include <sstream>

#include "trackphys/error.hpp"

namespace trackphys {
namespace {

// The first problem found, with its field's path under "CarSpec.vehicle.".
class Checker {
  public:
    void positive(const std::string& field, double value) {
        if (ok() && !(std::isfinite(value) && value > 0.0))
            why_ << kPrefix << field << " must be finite and > 0, got " << exact_text(value);
    }
    void non_negative(const std::string& field, double value) {
        if (ok() && !(std::isfinite(value) && value >= 0.0))
            why_ << kPrefix << field << " must be finite and >= 0, got " << exact_text(value);
    }
    void in_unit(const std::string& field, double value) {
        if (ok() && !(value >= 0.0 && value <= 1.0))
            why_ << kPrefix << field << " must be in [0, 1], got " << exact_text(value);
    }
    void require(bool condition, const std::string& field, const std::string& what) {
        if (ok() && !condition) why_ << kPrefix << field << " " << what;
    }
    void take(const std::string& problem) {
        if (ok() && !problem.empty()) why_ << problem;
    }
    bool ok() { return why_.tellp() == 0; }
    std::string str() const { return why_.str(); }

    static constexpr const char* kPrefix = "CarSpec.vehicle.";

  private:
    std::ostringstream why_;
};

void check_differential(Checker& check, const std::string& name, const DifferentialSpec& d) {
    check.non_negative(name + ".preload", d.preload);
    check.in_unit(name + ".locking", d.locking);
}

}  // namespace

std::string VehicleSpec::validate() const {
    Checker check;
    const std::string prefix = Checker::kPrefix;
    check.take(front_tyre.validate(prefix + "front_tyre."));
    check.take(rear_tyre.validate(prefix + "rear_tyre."));
    check.positive("wheel_inertia", wheel_inertia);

    const std::vector<TorquePoint>& curve = engine.torque_curve;
    check.require(!curve.empty() && curve.size() <= EngineSpec::max_torque_points,
                  "engine.torque_curve",
                  "must hold 1 to " + std::to_string(EngineSpec::max_torque_points) + " points");
    for (std::size_t k = 0; k < curve.size(); ++k) {
        const std::string point = "engine.torque_curve[" + std::to_string(k) + "]";
        check.non_negative(point + ".rpm", curve[k].rpm);
        check.non_negative(point + ".torque", curve[k].torque);
        check.require(k == 0 || curve[k].rpm > curve[k - 1].rpm, point + ".rpm",
                      "must exceed the previous point's");
    }
    check.positive("engine.idle_rpm", engine.idle_rpm);
    check.positive("engine.redline_rpm", engine.redline_rpm);
    check.require(engine.redline_rpm > engine.idle_rpm, "engine.redline_rpm",
                  "must exceed engine.idle_rpm");
    check.positive("engine.inertia", engine.inertia);
    check.non_negative("engine.friction_torque", engine.friction_torque);

    check.require(!gearbox.ratios.empty() && gearbox.ratios.size() <= 12, "gearbox.ratios",
                  "must hold 1 to 12 gears");
    for (std::size_t k = 0; k < gearbox.ratios.size(); ++k)
        check.positive("gearbox.ratios[" + std::to_string(k) + "]", gearbox.ratios[k]);
    check.positive("gearbox.final_drive", gearbox.final_drive);
    check.positive("gearbox.reverse_ratio", gearbox.reverse_ratio);
    check.positive("gearbox.shift_down_rpm", gearbox.shift_down_rpm);
    check.require(gearbox.shift_up_rpm > gearbox.shift_down_rpm, "gearbox.shift_up_rpm",
                  "must exceed gearbox.shift_down_rpm");
    check.require(gearbox.shift_up_rpm <= engine.redline_rpm, "gearbox.shift_up_rpm",
                  "must not exceed engine.redline_rpm");
    check.non_negative("gearbox.shift_time", gearbox.shift_time);
    check.positive("gearbox.clutch_engage_time", gearbox.clutch_engage_time);
    check.positive("gearbox.launch_rpm", gearbox.launch_rpm);
    // Above the redline the engine's torque at launch_rpm is the fuel cut's drag, which
    // would turn the wheels backwards under throttle; below idle the engine would stall.
    std::ostringstream launch_range;
    launch_range << "must be in [engine.idle_rpm, gearbox.shift_up_rpm] = ["
                 << exact_text(engine.idle_rpm) << ", " << exact_text(gearbox.shift_up_rpm)
                 << "], got " << exact_text(gearbox.launch_rpm);
    check.require(
        gearbox.launch_rpm >= engine.idle_rpm && gearbox.launch_rpm <= gearbox.shift_up_rpm,
        "gearbox.launch_rpm", launch_range.str());

    check_differential(check, "front_differential", front_differential);
    check_differential(check, "rear_differential", rear_differential);
    check_differential(check, "centre_differential", centre_differential);
    check.non_negative("max_brake_torque", max_brake_torque);
    check.non_negative("front_anti_roll", front_anti_roll);
    check.non_negative("rear_anti_roll", rear_anti_roll);
    check.positive("low_speed", low_speed);
    std::ostringstream rolling_range;
    rolling_range << "must be in [0, 0.1], got " << exact_text(rolling_resistance);
    check.require(rolling_resistance >= 0.0 && rolling_resistance <= 0.1, "rolling_resistance",
                  rolling_range.str());
    return check.str();
}

}  // namespace trackphys
