#pragma once

#include <CLI/CLI.hpp>

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

void add_drive_command(CLI::App& app);
void add_race_command(CLI::App& app);
void add_track_command(CLI::App& app);
void add_info_command(CLI::App& app);
void add_bench_command(CLI::App& app);
void add_view_command(CLI::App& app);
void add_bake_command(CLI::App& app);

}  // namespace trackphys::cli
