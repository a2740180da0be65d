#include "trackphys/io/scenario.hpp"

#include <cmath>
#include <sstream>

#include "car_spec_json_detail.hpp"
#include "json_reader.hpp"
#include "trackphys/error.hpp"
#include "trackphys/io/car_spec_json.hpp"
#include "trackphys/math/types.hpp"

namespace trackphys {
namespace {

using json_io::Json;
using json_io::ObjectReader;

// Appends "Scenario.<field> must be in [lo, hi], got x" when x is outside or not finite.
void check_range(std::ostringstream& why, const char* field, double x, double lo, double hi) {
    if (why.tellp() == 0 && !(std::isfinite(x) && x >= lo && x <= hi))
        why << "Scenario." << field << " must be in [" << exact_text(lo) << ", " << exact_text(hi)
            << "], got " << exact_text(x);
}

void read_track(ObjectReader& scenario, Scenario& s, const std::filesystem::path& base) {
    const Json* value = scenario.find("track");
    if (value == nullptr) return;
    ObjectReader track(*value, scenario.path_of("track"), scenario.source());
    if (int(track.has("seed")) + int(track.has("mesh")) + int(track.has("map")) > 1)
        json_io::fail(track.source(), track.path(),
                      "give one of 'seed' (a generated track), 'mesh' (a mesh file) or 'map' (a "
                      "baked map)");
    track.read("seed", s.seed);
    const auto read_file = [&](const char* key, std::filesystem::path& to) {
        std::string file;
        track.read(key, file);
        if (track.has(key) && file.empty())
            json_io::fail(track.source(), track.path_of(key), "empty file name");
        if (!file.empty()) to = base / file;
    };
    read_file("mesh", s.mesh);
    read_file("map", s.map);
    if (track.has("spawn")) {
        glm::dvec3 spawn(0.0);
        track.read("spawn", spawn);
        s.spawn = spawn;
    }
    if (track.has("heading_deg") && !s.spawn)
        json_io::fail(track.source(), track.path_of("heading_deg"),
                      "a heading applies to a spawn point (free mode): add 'spawn'");
    track.read("heading_deg", s.heading_deg);
    if (const Json* list = track.find("surfaces")) {
        if (!list->is_array())
            json_io::fail(track.source(), track.path_of("surfaces"),
                          "expected an array of surfaces ({\"grip\": g} by surface id)");
        for (std::size_t i = 0; i < list->size(); ++i) {
            ObjectReader surface((*list)[i], json_io::index_path(track.path_of("surfaces"), i),
                                 track.source());
            surface.read("grip", s.surfaces.emplace_back().grip);
            surface.finish();
        }
    }
    track.finish();
}

void read_car(ObjectReader& scenario, Scenario& s, const std::filesystem::path& base) {
    const Json* value = scenario.find("car");
    if (value == nullptr) return;
    if (value->is_string()) {
        const std::string file = value->get<std::string>();
        if (file.empty())
            json_io::fail(scenario.source(), scenario.path_of("car"), "empty file name");
        try {
            s.car = load_car_spec(base / file);
        } catch (const Error& e) {
            json_io::fail(scenario.source(), scenario.path_of("car"), e.what());
        }
    } else {
        s.car = json_io::car_spec_from_json(*value, scenario.path_of("car"), scenario.source());
    }
}

void read_driver(ObjectReader& scenario, Scenario& s) {
    const Json* autopilot = scenario.find("autopilot");
    const Json* inputs = scenario.find("inputs");
    const std::string& source = scenario.source();
    if (autopilot != nullptr && inputs != nullptr)
        json_io::fail(source, scenario.path(), "give either 'autopilot' or 'inputs', not both");
    if (autopilot != nullptr) {
        if (s.free_mode())
            json_io::fail(source, scenario.path_of("autopilot"),
                          "the autopilot drives the generated track from its start line: not with "
                          "track.spawn "
                          "(free mode drives by 'inputs')");
        ObjectReader in(*autopilot, scenario.path_of("autopilot"), source);
        in.read("target_speed_kmh", s.target_speed_kmh);
        in.finish();
    }
    if (inputs != nullptr) {
        if (!s.free_mode())
            json_io::fail(
                source, scenario.path_of("inputs"),
                "fixed inputs drive in free mode: add track.spawn (the generated track without a "
                "spawn point is driven by the autopilot)");
        ObjectReader in(*inputs, scenario.path_of("inputs"), source);
        in.read("throttle", s.inputs.throttle);
        in.read("brake", s.inputs.brake);
        in.read("steer", s.inputs.steer);
        in.finish();
    }
}

}  // namespace

std::string Scenario::validate() const {
    std::ostringstream why;
    if (!mesh.empty() && !spawn)
        why << "Scenario.mesh needs a spawn point (Scenario.spawn) to place the car on it";
    if (why.tellp() == 0 && !mesh.empty() && !map.empty())
        why << "Scenario.map and Scenario.mesh both name the track: give one";
    if (why.tellp() == 0 && spawn && !is_finite(*spawn))
        why << "Scenario.spawn must be finite, got (" << spawn->x << ", " << spawn->y << ", "
            << spawn->z << ")";
    if (why.tellp() == 0 && !std::isfinite(heading_deg))
        why << "Scenario.heading_deg must be finite, got " << exact_text(heading_deg);
    if (why.tellp() == 0) why << check_surface_table(surfaces, "Scenario.surfaces");
    if (why.tellp() == 0 && !(target_speed_kmh > 0.0 && target_speed_kmh <= max_target_speed_kmh))
        why << "Scenario.target_speed_kmh must be in (0, " << exact_text(max_target_speed_kmh)
            << "], got " << exact_text(target_speed_kmh);
    check_range(why, "inputs.throttle", inputs.throttle, -1.0, 1.0);
    check_range(why, "inputs.brake", inputs.brake, 0.0, 1.0);
    check_range(why, "inputs.steer", inputs.steer, -1.0, 1.0);
    check_range(why, "cars", cars, 1.0, max_scenario_cars);
    if (why.tellp() == 0 && cars > 1 && (free_mode() || !mesh.empty() || !map.empty()))
        why << "Scenario.cars: a field of " << cars
            << " cars races from the generated track's grid (track.seed), not on a mesh, a map "
               "or from a spawn point";
    check_range(why, "laps", laps, 0.0, max_scenario_laps);
    check_range(why, "seconds", seconds, 0.0, max_scenario_seconds);
    if (why.tellp() == 0 && free_mode() && laps > 0)
        why << "Scenario.laps needs the generated track's centreline: free mode (a spawn point) "
               "drives for "
               "Scenario.seconds";
    if (why.tellp() == 0 && free_mode() && seconds == 0.0)
        why << "Scenario.seconds must be > 0 in free mode (a spawn point): laps need the generated "
               "track";
    if (why.tellp() == 0) why << car.validate();
    return why.str();
}

Scenario parse_scenario(std::string_view json_text, const std::string& source,
                        const std::filesystem::path& base_folder) {
    const Json document = json_io::parse_document(json_text, source);
    ObjectReader in(document, "", source);
    Scenario s;
    read_track(in, s, base_folder);
    read_car(in, s, base_folder);
    read_driver(in, s);
    in.read("cars", s.cars);
    in.read("laps", s.laps);
    in.read("seconds", s.seconds);
    in.finish();
    if (const std::string why = s.validate(); !why.empty()) json_io::fail(source, "", why);
    return s;
}

Scenario load_scenario(const std::filesystem::path& file) {
    const std::string text = json_io::read_text_file(file, "scenario");
    return parse_scenario(text, "scenario '" + file.string() + "'", file.parent_path());
}

std::string scenario_to_json(const Scenario& s) {
    Json track;
    if (!s.map.empty())
        track["map"] = s.map.string();
    else if (!s.mesh.empty())
        track["mesh"] = s.mesh.string();
    else
        track["seed"] = s.seed;
    if (s.spawn) {
        track["spawn"] = Json::array({s.spawn->x, s.spawn->y, s.spawn->z});
        track["heading_deg"] = s.heading_deg;
    }
    if (!s.surfaces.empty()) {
        Json& surfaces = track["surfaces"] = Json::array();
        for (const Surface& surface : s.surfaces) surfaces.push_back({{"grip", surface.grip}});
    }
    Json out = {{"track", std::move(track)}, {"car", json_io::car_spec_to_json_value(s.car)}};
    if (s.free_mode())
        out["inputs"] = {
            {"throttle", s.inputs.throttle}, {"brake", s.inputs.brake}, {"steer", s.inputs.steer}};
    else
        out["autopilot"] = {{"target_speed_kmh", s.target_speed_kmh}};
    if (s.cars != 1) out["cars"] = s.cars;
    out["laps"] = s.laps;
    out["seconds"] = s.seconds;
    // A mesh name from the command line need not be UTF-8: replace what JSON cannot hold.
    return out.dump(2, ' ', false, Json::error_handler_t::replace) + "\n";
}

}  // namespace trackphys
