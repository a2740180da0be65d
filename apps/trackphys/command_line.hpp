#pragma once

#include <CLI/CLI.hpp>

namespace trackphys::cli {

/// Adds every subcommand of `trackphys` to app, each with its options and the callback that
/// runs it (command_line.cpp). A callback reports failure by throwing trackphys::Error or
/// CLI::Error.
void add_commands(CLI::App& app);

}  // namespace trackphys::cli
