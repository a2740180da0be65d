#include "trackphys/io/car_spec_json.hpp"

#include <array>
#include <utility>

#include "car_spec_json_detail.hpp"
#include "trackphys/error.hpp"
#include "vehicle_spec_json.hpp"

namespace trackphys {
namespace json_io {
namespace {

constexpr std::array<std::pair<EllipsoidRole, const char*>, 3> kRoles = {{
    {EllipsoidRole::body, "body"},
    {EllipsoidRole::front_wheel, "front_wheel"},
    {EllipsoidRole::rear_wheel, "rear_wheel"},
}};

const char* role_name(EllipsoidRole role) {
    for (const auto& [value, name] : kRoles)
        if (value == role) return name;
    return "body";  // unreachable: kRoles lists every role
}

EllipsoidRole role_from_json(ObjectReader& in) {
    std::string name;
    in.read("role", name);
    for (const auto& [value, known] : kRoles)
        if (name == known) return value;
    fail(in.source(), in.path_of("role"),
         "unknown role " + quoted_text(name) + " (expected body, front_wheel or rear_wheel)");
}

CarEllipsoid ellipsoid_from_json(const Json& value, const std::string& path,
                                 const std::string& source) {
    ObjectReader in(value, path, source);
    CarEllipsoid e;
    // No default car ellipsoid to fall back on: where and how big it is must be said.
    in.require("center"), in.require("semi_axes"), in.require("role");
    in.read("center", e.center);
    in.read("semi_axes", e.semi_axes);
    in.read("orientation", e.orientation);
    e.role = role_from_json(in);
    in.finish();
    return e;
}

void material_from_json(ObjectReader& parent, const char* key, ContactMaterial& m) {
    const Json* value = parent.find(key);
    if (value == nullptr) return;
    ObjectReader in(*value, parent.path_of(key), parent.source());
    in.read("stiffness", m.stiffness);
    in.read("damping", m.damping);
    in.read("friction", m.friction);
    in.read("slip_speed", m.slip_speed);
    in.finish();
}

Json material_to_json(const ContactMaterial& m) {
    return {{"stiffness", m.stiffness},
            {"damping", m.damping},
            {"friction", m.friction},
            {"slip_speed", m.slip_speed}};
}

Json vector_to_json(const glm::dvec3& v) { return Json::array({v.x, v.y, v.z}); }

}  // namespace

CarSpec car_spec_from_json(const Json& value, const std::string& path, const std::string& source) {
    ObjectReader in(value, path, source);
    // "model" picks the preset the other keys change.
    CarSpec spec = CarSpec::default_car();
    if (in.has("model")) {
        std::string model;
        in.read("model", model);
        try {
            spec = CarSpec::preset(model);
        } catch (const Error& e) {
            fail(source, in.path_of("model"), e.what());
        }
    }
    if (const Json* mass = in.find("mass")) {
        ObjectReader m(*mass, in.path_of("mass"), source);
        m.read("mass", spec.mass.mass);
        m.read("principal_inertia", spec.mass.principal_inertia);
        m.finish();
    }
    if (const Json* list = in.find("ellipsoids")) {
        if (!list->is_array())
            fail(source, in.path_of("ellipsoids"), "expected an array of ellipsoids");
        spec.ellipsoids.clear();
        for (std::size_t i = 0; i < list->size(); ++i)
            spec.ellipsoids.push_back(
                ellipsoid_from_json((*list)[i], index_path(in.path_of("ellipsoids"), i), source));
    }
    material_from_json(in, "body_contact", spec.body_contact);
    material_from_json(in, "wheel_contact", spec.wheel_contact);
    material_from_json(in, "car_contact", spec.car_contact);
    if (const Json* suspension = in.find("suspension")) {
        ObjectReader s(*suspension, in.path_of("suspension"), source);
        s.read("stiffness", spec.suspension.stiffness);
        s.read("damping", spec.suspension.damping);
        s.read("travel", spec.suspension.travel);
        s.finish();
    }
    in.read("rear_grip_factor", spec.rear_grip_factor);
    in.read("max_drive_force", spec.max_drive_force);
    in.read("front_drive_share", spec.front_drive_share);
    in.read("traction_limit", spec.traction_limit);
    in.read("max_drive_power", spec.max_drive_power);
    in.read("max_reverse_speed", spec.max_reverse_speed);
    in.read("max_brake_force", spec.max_brake_force);
    in.read("front_brake_share", spec.front_brake_share);
    in.read("max_steer_angle", spec.max_steer_angle);
    in.read("deep_contact_fraction", spec.deep_contact_fraction);
    in.read("drag_area", spec.drag_area);
    in.read("downforce_area", spec.downforce_area);
    in.read("air_density", spec.air_density);
    if (const Json* vehicle = in.find("vehicle")) {
        if (!spec.vehicle)
            fail(source, in.path_of("vehicle"),
                 "the arcade car has no vehicle model: give \"model\": \"gt\" or "
                 "\"formula\" first");
        vehicle_from_json(*vehicle, in.path_of("vehicle"), source, *spec.vehicle);
    }
    in.finish();
    // The physical checks live in one place: CarSpec::validate names the field.
    if (const std::string why = spec.validate(); !why.empty()) fail(source, path, why);
    return spec;
}

Json car_ellipsoids_to_json(std::span<const CarEllipsoid> ellipsoids) {
    Json out = Json::array();
    for (const CarEllipsoid& e : ellipsoids)
        out.push_back({{"center", vector_to_json(e.center)},
                       {"semi_axes", vector_to_json(e.semi_axes)},
                       {"orientation", Json::array({e.orientation.w, e.orientation.x,
                                                    e.orientation.y, e.orientation.z})},
                       {"role", role_name(e.role)}});
    return out;
}

Json car_spec_to_json_value(const CarSpec& spec) {
    Json out = {
        {"model", spec.vehicle ? spec.vehicle->model : std::string("arcade")},
        {"mass",
         {{"mass", spec.mass.mass},
          {"principal_inertia", vector_to_json(spec.mass.principal_inertia)}}},
        {"ellipsoids", car_ellipsoids_to_json(spec.ellipsoids)},
        {"body_contact", material_to_json(spec.body_contact)},
        {"wheel_contact", material_to_json(spec.wheel_contact)},
        {"car_contact", material_to_json(spec.car_contact)},
        {"suspension",
         {{"stiffness", spec.suspension.stiffness},
          {"damping", spec.suspension.damping},
          {"travel", spec.suspension.travel}}},
        {"rear_grip_factor", spec.rear_grip_factor},
        {"max_drive_force", spec.max_drive_force},
        {"front_drive_share", spec.front_drive_share},
        {"traction_limit", spec.traction_limit},
        {"max_drive_power", spec.max_drive_power},
        {"max_reverse_speed", spec.max_reverse_speed},
        {"max_brake_force", spec.max_brake_force},
        {"front_brake_share", spec.front_brake_share},
        {"max_steer_angle", spec.max_steer_angle},
        {"deep_contact_fraction", spec.deep_contact_fraction},
        {"drag_area", spec.drag_area},
        {"downforce_area", spec.downforce_area},
        {"air_density", spec.air_density},
    };
    if (spec.vehicle) out["vehicle"] = vehicle_to_json(*spec.vehicle);
    return out;
}

}  // namespace json_io

CarSpec parse_car_spec(std::string_view json_text, const std::string& source) {
    return json_io::car_spec_from_json(json_io::parse_document(json_text, source), "", source);
}

CarSpec load_car_spec(const std::filesystem::path& file) {
    const std::string source = "car spec '" + file.string() + "'";
    return parse_car_spec(json_io::read_text_file(file, "car spec"), source);
}

std::string car_spec_to_json(const CarSpec& spec) {
    return json_io::car_spec_to_json_value(spec).dump(2) + "\n";
}

}  // namespace trackphys
