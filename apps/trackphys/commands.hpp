#pragma once

#include <cstdio>
#include <filesystem>
#include <span>
#include <string>
#include <utility>

#include <CLI/CLI.hpp>

#include "trackphys/error.hpp"

namespace trackphys::cli {

// Each subcommand of `trackphys` lives in its own file and registers itself here: it adds
// its options to a new subcommand of app and sets the callback that runs it. A callback
// reports failure by throwing (trackphys::Error or CLI::Error); main turns that into a
// message on stderr and a non-zero exit.

/// Rejects a leading minus sign: CLI11 reads "-1" into an unsigned option as 2^64 - 1.
inline CLI::Validator not_negative() {
    return CLI::Validator(
        [](const std::string& text) {
            return text.rfind('-', 0) == 0 ? std::string("must be >= 0, got " + text) : "";
        },
        "UINT", "not_negative");
}

/// A number as messages show it, %g-style like Scenario's ("2", "1e+300"), never
/// std::to_string's six decimals or its 300 digits.
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

/// Refuses an explicit --laps 0 or --seconds 0: Scenario reads 0 as "not given" and would
/// drive a lap for a user who asked for none.
inline void refuse_zero_duration(const CLI::App& command, int laps, double seconds) {
    if (command.count("--laps") > 0 && laps == 0)
        throw Error("--laps must be >= 1, got 0 (leave it out for the default)");
    if (command.count("--seconds") > 0 && seconds == 0.0)
        throw Error("--seconds must be > 0, got 0 (leave it out for the default)");
}

/// Pairs of a Scenario field and the option that sets it ({"Scenario.laps", "--laps"}).
using FieldOptions = std::span<const std::pair<const char*, const char*>>;

/// Throws Scenario::validate()'s message `why` named after its source: the option that set
/// the field it names when that option was given, else the scenario file when there is one.
[[noreturn]] inline void fail_scenario(const std::string& why, FieldOptions fields,
                                       const CLI::App& command,
                                       const std::filesystem::path& scenario_file) {
    for (const auto& [field, option] : fields)
        if (why.rfind(field, 0) == 0 && command.count(option) > 0)
            throw Error(std::string(option) + ": " + why);
    if (!scenario_file.empty()) throw Error("scenario '" + scenario_file.string() + "': " + why);
    throw Error(why);
}

void add_drive_command(CLI::App& app);
void add_race_command(CLI::App& app);
void add_track_command(CLI::App& app);
void add_info_command(CLI::App& app);
void add_bench_command(CLI::App& app);
void add_view_command(CLI::App& app);
void add_bake_command(CLI::App& app);

}  // namespace trackphys::cli
