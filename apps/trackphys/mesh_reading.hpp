#pragma once

#include <filesystem>

#include "trackphys/geometry/triangle_mesh.hpp"
#include "trackphys/io/mesh_io.hpp"
#include "trackphys/io/mesh_load_limits.hpp"

namespace trackphys::cli {

/// load_mesh as the commands read a mesh file: a bar of the triangles placed on a terminal
/// (a file of millions takes seconds), and a stop at the next report once Ctrl-C came under
/// the command's InterruptGuard.
TriangleMesh read_mesh(const std::filesystem::path& file, MeshLoadReport& report,
                       const MeshLoadLimits& limits);

/// read_mesh without the report.
TriangleMesh read_mesh(const std::filesystem::path& file, const MeshLoadLimits& limits);

}  // namespace trackphys::cli
