#pragma once

#include <CLI/CLI.hpp>

namespace trackphys::cli {

// Each subcommand of `trackphys` lives in its own file and registers itself here: it adds
// its options to a new subcommand of app and sets the callback that runs it. A callback
// reports failure by throwing (trackphys::Error or CLI::Error); main turns that into a
// message on stderr and a non-zero exit.

void add_drive_command(CLI::App& app);
void add_track_command(CLI::App& app);
void add_info_command(CLI::App& app);
void add_bench_command(CLI::App& app);

}  // namespace trackphys::cli
