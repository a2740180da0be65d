#include "vehicle_spec_json.hpp"

#include <utility>

#include "trackphys/error.hpp"

namespace trackphys::json_io {
namespace {

// A nested object read over out when key is present.
template <typename Reader>
void nested(ObjectReader& parent, const char* key, Reader read_into) {
    const Json* value = parent.find(key);
    if (value == nullptr) return;
    ObjectReader in(*value, parent.path_of(key), parent.source());
    read_into(in);
    in.finish();
}

void read_bool(ObjectReader& in, const char* key, bool& out) {
    const Json* value = in.find(key);
    if (value == nullptr) return;
    if (!value->is_boolean()) fail(in.source(), in.path_of(key), "expected true or false");
    out = value->get<bool>();
}

std::vector<double> read_list(ObjectReader& in, const char* key, std::vector<double> out) {
    const Json* value = in.find(key);
    if (value == nullptr) return out;
    if (!value->is_array()) fail(in.source(), in.path_of(key), "expected an array of numbers");
    return to_numbers(*value, value->size(), in.path_of(key), in.source());
}

void read_curve(ObjectReader& in, MagicFormulaCurve& c) {
    in.read("stiffness", c.stiffness);
    in.read("shape", c.shape);
    in.read("curvature", c.curvature);
    in.read("friction", c.friction);
    in.read("friction_load_slope", c.friction_load_slope);
}

void read_tyre(ObjectReader& in, TyreSpec& t) {
    nested(in, "longitudinal", [&](ObjectReader& c) { read_curve(c, t.longitudinal); });
    nested(in, "lateral", [&](ObjectReader& c) { read_curve(c, t.lateral); });
    in.read("nominal_load", t.nominal_load);
    in.read("longitudinal_relaxation", t.longitudinal_relaxation);
    in.read("lateral_relaxation", t.lateral_relaxation);
}

void read_engine(ObjectReader& in, EngineSpec& e) {
    if (const Json* curve = in.find("torque_curve")) {
        const std::string path = in.path_of("torque_curve");
        if (!curve->is_array()) fail(in.source(), path, "expected an array of [rpm, N m] pairs");
        e.torque_curve.clear();
        for (std::size_t k = 0; k < curve->size(); ++k) {
            const std::vector<double> point =
                to_numbers((*curve)[k], 2, index_path(path, k), in.source());
            e.torque_curve.push_back({point[0], point[1]});
        }
    }
    in.read("idle_rpm", e.idle_rpm);
    in.read("redline_rpm", e.redline_rpm);
    in.read("inertia", e.inertia);
    in.read("friction_torque", e.friction_torque);
}

void read_gearbox(ObjectReader& in, GearboxSpec& g) {
    g.ratios = read_list(in, "ratios", std::move(g.ratios));
    in.read("final_drive", g.final_drive);
    in.read("shift_up_rpm", g.shift_up_rpm);
    in.read("shift_down_rpm", g.shift_down_rpm);
    in.read("shift_time", g.shift_time);
    in.read("clutch_engage_time", g.clutch_engage_time);
    in.read("launch_rpm", g.launch_rpm);
    in.read("reverse_ratio", g.reverse_ratio);
}

void read_differential(ObjectReader& in, DifferentialSpec& d) {
    if (in.has("kind")) {
        std::string kind;
        in.read("kind", kind);
        if (kind == "open")
            d.kind = DifferentialKind::open;
        else if (kind == "limited_slip")
            d.kind = DifferentialKind::limited_slip;
        else
            fail(in.source(), in.path_of("kind"),
                 "unknown kind " + quoted_text(kind) + " (expected open or limited_slip)");
    }
    in.read("preload", d.preload);
    in.read("locking", d.locking);
}

Json curve_to_json(const MagicFormulaCurve& c) {
    return {{"stiffness", c.stiffness},
            {"shape", c.shape},
            {"curvature", c.curvature},
            {"friction", c.friction},
            {"friction_load_slope", c.friction_load_slope}};
}

Json tyre_to_json(const TyreSpec& t) {
    return {{"longitudinal", curve_to_json(t.longitudinal)},
            {"lateral", curve_to_json(t.lateral)},
            {"nominal_load", t.nominal_load},
            {"longitudinal_relaxation", t.longitudinal_relaxation},
            {"lateral_relaxation", t.lateral_relaxation}};
}

Json differential_to_json(const DifferentialSpec& d) {
    return {{"kind", d.kind == DifferentialKind::open ? "open" : "limited_slip"},
            {"preload", d.preload},
            {"locking", d.locking}};
}

}  // namespace

void vehicle_from_json(const Json& value, const std::string& path, const std::string& source,
                       VehicleSpec& v) {
    ObjectReader in(value, path, source);
    nested(in, "front_tyre", [&](ObjectReader& t) { read_tyre(t, v.front_tyre); });
    nested(in, "rear_tyre", [&](ObjectReader& t) { read_tyre(t, v.rear_tyre); });
    in.read("wheel_inertia", v.wheel_inertia);
    nested(in, "engine", [&](ObjectReader& e) { read_engine(e, v.engine); });
    nested(in, "gearbox", [&](ObjectReader& g) { read_gearbox(g, v.gearbox); });
    nested(in, "front_differential",
           [&](ObjectReader& d) { read_differential(d, v.front_differential); });
    nested(in, "rear_differential",
           [&](ObjectReader& d) { read_differential(d, v.rear_differential); });
    nested(in, "centre_differential",
           [&](ObjectReader& d) { read_differential(d, v.centre_differential); });
    in.read("max_brake_torque", v.max_brake_torque);
    read_bool(in, "anti_lock", v.anti_lock);
    read_bool(in, "traction_control", v.traction_control);
    in.read("front_anti_roll", v.front_anti_roll);
    in.read("rear_anti_roll", v.rear_anti_roll);
    in.read("low_speed", v.low_speed);
    in.read("rolling_resistance", v.rolling_resistance);
    in.finish();
}

Json vehicle_to_json(const VehicleSpec& v) {
    Json curve = Json::array();
    for (const TorquePoint& p : v.engine.torque_curve) curve.push_back({p.rpm, p.torque});
    return {
        {"front_tyre", tyre_to_json(v.front_tyre)},
        {"rear_tyre", tyre_to_json(v.rear_tyre)},
        {"wheel_inertia", v.wheel_inertia},
        {"engine",
         {{"torque_curve", std::move(curve)},
          {"idle_rpm", v.engine.idle_rpm},
          {"redline_rpm", v.engine.redline_rpm},
          {"inertia", v.engine.inertia},
          {"friction_torque", v.engine.friction_torque}}},
        {"gearbox",
         {{"ratios", v.gearbox.ratios},
          {"final_drive", v.gearbox.final_drive},
          {"shift_up_rpm", v.gearbox.shift_up_rpm},
          {"shift_down_rpm", v.gearbox.shift_down_rpm},
          {"shift_time", v.gearbox.shift_time},
          {"clutch_engage_time", v.gearbox.clutch_engage_time},
          {"launch_rpm", v.gearbox.launch_rpm},
          {"reverse_ratio", v.gearbox.reverse_ratio}}},
        {"front_differential", differential_to_json(v.front_differential)},
        {"rear_differential", differential_to_json(v.rear_differential)},
        {"centre_differential", differential_to_json(v.centre_differential)},
        {"max_brake_torque", v.max_brake_torque},
        {"anti_lock", v.anti_lock},
        {"traction_control", v.traction_control},
        {"front_anti_roll", v.front_anti_roll},
        {"rear_anti_roll", v.rear_anti_roll},
        {"low_speed", v.low_speed},
        {"rolling_resistance", v.rolling_resistance},
    };
}

}  // namespace trackphys::json_io
