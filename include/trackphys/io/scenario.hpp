#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec3.hpp>

#include "trackphys/dynamics/car.hpp"
#include "trackphys/dynamics/car_spec.hpp"
#include "trackphys/export.hpp"
#include "trackphys/math/types.hpp"
#include "trackphys/track/track_params.hpp"
#include "trackphys/world/surface.hpp"

/// Scenarios: what `trackphys drive --scenario FILE` drives, as a value and as a JSON file.
///
///     {
///       "track": {"seed": 7},                  the generated track of that seed, or
///       "track": {"mesh": "g-track-1.ac", "spawn": [0, 50, 0], "heading_deg": 90}, or
///       "track": {"map": "oval.tpmap"},        a baked map (trackphys bake; spawn optional)
///       "track": {..., "surfaces": [{"grip": 1}, {"grip": 0.6}]},   grips by surface id
///       "car": {...} or "car.json",            inline (car_spec_json.hpp) or a car spec file
///       "autopilot": {"target_speed_kmh": 600},       drives the generated track, or
///       "inputs": {"throttle": 0.5, "brake": 0, "steer": 0},   fixed inputs, needs a spawn
///       "cars": 20,                            a field: `trackphys race` (drive: 1)
///       "laps": 1,
///       "seconds": 30
///     }
///
/// Every key is optional; a key left out keeps Scenario's default (below): `{}` is one
/// lap of the seed-7 track by autopilot at 600 km/h with the default car. A spawn point
/// (track.spawn) switches to free mode: the car lands on the surface below it and drives
/// with fixed inputs; a mesh needs one, and so does a map baked from a mesh (a map baked from
/// a generated track keeps its centreline for the autopilot). Relative file names
/// (track.mesh, track.map, a car file) are relative to the scenario file's folder. A race
/// (`cars` above 1) starts every car, of the scenario's car spec, from the generated track's
/// grid, the autopilots' target speeds spread from 70% of target_speed_kmh to all of it.

namespace trackphys {

/// Longest drive a scenario may ask for (simulated s, and laps): the drive command keeps a
/// few hundred bytes per update for its report, so a day is about a gigabyte.
inline constexpr double max_scenario_seconds = 86400.0;
inline constexpr int max_scenario_laps = 1000;
/// Fastest autopilot target (km/h): the design's 1000 km/h with margin.
inline constexpr double max_target_speed_kmh = 1500.0;
/// Most cars in a race (`trackphys race --cars`).
inline constexpr int max_scenario_cars = 128;

/// One drive: the track, the car, who drives it and for how long.
struct TRACKPHYS_API Scenario {
    std::uint64_t seed = kDemoTrackSeed;  ///< the generated track's seed (when mesh is empty)
    std::filesystem::path mesh;           ///< drive on this mesh file instead (needs spawn)
    std::filesystem::path map;            ///< or on this baked map (io/map_file.hpp)
    /// Free mode: the car starts upright above this point (m) and lands on the surface
    /// below it; it drives with `inputs` instead of the autopilot.
    std::optional<glm::dvec3> spawn;
    double heading_deg = 0.0;  ///< free mode: about +Y, 0 = +X, 90 = -Z (degrees)
    /// The grip of the track's surfaces by id (TriangleMesh::surfaces: `trackphys info`
    /// lists a mesh's; the generated track's road 0, its walls 1), from id 0; ids past the
    /// list are the dry road (grip 1). Empty: every surface is the dry road.
    std::vector<Surface> surfaces;
    CarSpec car = CarSpec::default_car();
    double target_speed_kmh = 600.0;  ///< autopilot: speed on straights, (0, 1500]
    /// Free mode: fixed throttle (-1..1, < 0 reverse), brake (0..1) and steer (-1..1).
    CarInputs inputs{0.5, 0.0, 0.0};
    /// Duration: laps of the generated track (autopilot only) and/or simulated seconds,
    /// whichever ends first (the command line's drive and race fail when the seconds end
    /// before the laps); both 0 means one lap (autopilot). Free mode needs seconds.
    int laps = 0;
    double seconds = 0.0;
    /// Cars in the field: 1 drives alone (`trackphys drive`), more race from the generated
    /// track's grid (`trackphys race`), in [1, max_scenario_cars].
    int cars = 1;

    bool free_mode() const { return spawn.has_value(); }

    /// Empty when the scenario can be driven; otherwise the first problem, naming the field
    /// ("Scenario.seconds must be in [0, 86400], got -1"; the car's by CarSpec::validate).
    std::string validate() const;
};

/// The scenario in text (JSON). source names the text in messages (e.g. "scenario
/// 'race.json'"); relative file names in it are taken relative to base_folder. Throws
/// trackphys::Error naming source and the problem: malformed JSON (line and column), a
/// duplicate or unknown key (with its JSON path), a value of the wrong type or not finite,
/// both track.seed and track.mesh, both "autopilot" and "inputs", "autopilot" with a spawn
/// point, "inputs" or track.heading_deg without one, the car (see parse_car_spec), or
/// whatever Scenario::validate() rejects.
TRACKPHYS_API Scenario parse_scenario(std::string_view json_text,
                                      const std::string& source = "scenario",
                                      const std::filesystem::path& base_folder = {});

/// parse_scenario of a file's contents, relative names taken from the file's folder; the message
/// also names the file when it is missing, a folder or a device, unreadable, empty or larger than
/// 16 MiB.
TRACKPHYS_API Scenario load_scenario(const std::filesystem::path& file);

/// scenario as a JSON document (the car inline, every key that applies to its mode: the
/// seed or the mesh, the autopilot or the inputs): what parse_scenario reads back into a
/// scenario that drives the same.
TRACKPHYS_API std::string scenario_to_json(const Scenario& scenario);

}  // namespace trackphys
