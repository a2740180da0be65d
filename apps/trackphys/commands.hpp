#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "trackphys/error.hpp"
#include "trackphys/io/mesh_load_limits.hpp"
#include "trackphys/io/scenario.hpp"
#include "trackphys/track/track_params.hpp"

namespace trackphys::cli {

// Each subcommand of `trackphys` runs in its own file, from a plain struct of its options.
// Only command_line.cpp (which declares every option and help text and calls the run
// functions) and main.cpp (which parses) include CLI11: it is header-only and slow to
// compile. A run function reports failure by throwing trackphys::Error; main turns that
// into a message on stderr and a non-zero exit.

/// Whether the command line gave an option ("--laps"), for the rules that tell a value given
/// from a default.
using OptionGiven = std::function<bool(const std::string& option)>;

/// A lap that takes longer than this (simulated) means a car is stuck: drive and race given
/// laps give up after this many seconds a lap.
inline constexpr double kMaxSecondsPerLap = 600.0;

/// The cells (m on x and z, a collider each) `bake` and `drive --mesh` split a mesh file into
/// (collider_build.hpp); `bake --chunk` changes it.
inline constexpr double kDefaultChunkM = 100.0;

/// A time or length as messages describe it, %g-style ("2", "1e+300"), never
/// std::to_string's six decimals or its 300 digits. A value checked against a bound is
/// shown by exact_text instead, so that one just past the bound does not read as the bound.
inline std::string shown(double x) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", x);
    return text;
}

/// Every command's --threads range, WorldSettings.threads's.
inline void check_threads(long long threads) {
    if (threads < 0 || threads > 256)
        throw Error("--threads must be in [0, 256] (0: the hardware's count), got " +
                    std::to_string(threads));
}

/// Refuses an explicit --laps or --seconds out of its range, 0 or less (or NaN) included:
/// Scenario reads 0 as "not given" and would drive a lap for a user who asked for none, and
/// its range message ("in [0, 86400]") would offer 0.
inline void check_duration_options(const OptionGiven& given, int laps, double seconds) {
    const char* default_hint = " (leave it out for the default)";
    if (given("--laps") && (laps <= 0 || laps > max_scenario_laps))
        throw Error("--laps must be in [1, " + std::to_string(max_scenario_laps) + "], got " +
                    std::to_string(laps) + (laps <= 0 ? default_hint : ""));
    if (given("--seconds") && !(seconds > 0.0 && seconds <= max_scenario_seconds))  // NaN too
        throw Error("--seconds must be in (0, " + shown(max_scenario_seconds) + "], got " +
                    exact_text(seconds) + (seconds <= 0.0 ? default_hint : ""));
}

/// Refuses a mesh limit (--max-triangles...) given to a run that reads no mesh file, where
/// it would limit nothing: `command` ("drive") reads `instead` ("a generated track").
inline void refuse_unused_mesh_limits(const OptionGiven& given, const std::string& command,
                                      const std::string& instead) {
    for (const char* option : {"--max-triangles", "--max-vertices", "--max-bytes",
                               "--max-polygon-corners", "--max-nesting"})
        if (given(option))
            throw Error(std::string(option) + " limits a mesh file, but this " + command +
                        " reads none (" + instead + ")");
}

/// --surface-grips G0,G1,... as Scenario::surfaces (checked with the scenario).
inline std::vector<Surface> surfaces_of(const std::vector<double>& grips) {
    std::vector<Surface> surfaces;
    for (double grip : grips) surfaces.push_back({grip});
    return surfaces;
}

/// Pairs of a Scenario field and the option that sets it ({"Scenario.laps", "--laps"}).
using FieldOptions = std::span<const std::pair<const char*, const char*>>;

/// Throws Scenario::validate()'s message `why` named after its source: the option that set
/// the field it names when that option was given, else the scenario file when there is one.
[[noreturn]] inline void fail_scenario(const std::string& why, FieldOptions fields,
                                       const OptionGiven& given,
                                       const std::filesystem::path& scenario_file) {
    for (const auto& [field, option] : fields)
        if (why.rfind(field, 0) == 0 && given(option))
            throw Error(std::string(option) + ": " + why);
    if (!scenario_file.empty()) throw Error("scenario '" + scenario_file.string() + "': " + why);
    throw Error(why);
}

/// `trackphys drive`. The scene options (--seed to --steer, --laps, --seconds) are read into
/// a default Scenario; the drive copies those given explicitly over the scenario file.
struct DriveOptions {
    std::string track = "default";
    std::filesystem::path scenario_file, car_file;
    std::string car_preset;
    bool print_car = false;
    bool print_scenario = false;
    Scenario flags;
    std::vector<double> spawn;
    std::vector<double> surface_grips;  ///< --surface-grips, by surface id
    std::filesystem::path json, trace, record, svg, telemetry;
    std::pair<std::string, std::string> save_at;  // T FILE
    std::filesystem::path resume;
    MeshLoadLimits mesh_limits;
};
void run_drive(const DriveOptions& options, const OptionGiven& given);

/// `trackphys race`.
struct RaceOptions {
    std::filesystem::path scenario_file;
    std::uint64_t seed = kDemoTrackSeed;
    std::size_t cars = 20;
    int laps = 0;
    double seconds = 0.0;
    int threads = 0;
    std::filesystem::path map;          ///< a baked map instead of the generated track
    std::vector<double> surface_grips;  ///< --surface-grips, by surface id
    std::filesystem::path json, trace, record, svg;
};
void run_race(const RaceOptions& options, const OptionGiven& given);

/// `trackphys track`.
struct TrackOptions {
    TrackParams params;
    std::filesystem::path out;  ///< mesh file (any format save_mesh writes), empty for none
    std::filesystem::path svg;  ///< picture, empty for none
    /// (TrackParams field, the flag that sets it), for the generator's error messages.
    std::vector<std::pair<std::string, std::string>> flag_of_field;
};
void run_track(const TrackOptions& options);

/// `trackphys info`.
struct InfoOptions {
    std::string file;
    bool json = false;
    MeshLoadLimits mesh_limits;
};
void run_info(const InfoOptions& options);

/// `trackphys bake`.
struct BakeOptions {
    std::filesystem::path mesh;
    std::uint64_t seed = kDemoTrackSeed;
    std::filesystem::path out;
    double chunk_m = kDefaultChunkM;
    int threads = 0;
    MeshLoadLimits mesh_limits;
};
void run_bake(const BakeOptions& options, const OptionGiven& given);

/// `trackphys bench`, which only says where the benchmarks went (always throws).
[[noreturn]] void run_bench();

/// `trackphys view`.
struct ViewOptions {
    std::filesystem::path recording;
    std::filesystem::path out;
    MeshLoadLimits mesh_limits;
};
void run_view(const ViewOptions& options);

}  // namespace trackphys::cli
