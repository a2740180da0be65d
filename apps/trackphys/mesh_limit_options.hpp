#pragma once

#include <CLI/CLI.hpp>

#include "trackphys/io/mesh_load_limits.hpp"

namespace trackphys::cli {

/// Adds --max-triangles, --max-vertices, --max-bytes and --max-nesting (MeshLoadLimits,
/// defaults shown in --help) to a command that loads mesh files, in an option group of their
/// own, writing into limits.
void add_mesh_limit_options(CLI::App& command, MeshLoadLimits& limits);

}  // namespace trackphys::cli
