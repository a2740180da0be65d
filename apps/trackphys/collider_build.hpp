#pragma once

#include <filesystem>

#include "trackphys/io/map_file.hpp"
#include "trackphys/io/mesh_load_limits.hpp"
#include "trackphys/track/track.hpp"

namespace trackphys::cli {

/// A mesh file's colliders and plane trees: the file split into `chunk_m` cells on x and z
/// (split_into_chunks), built by bake_map on `threads` (0: one per core). What `bake` writes
/// and `drive --mesh` drives on, so that the two drive alike. While the colliders are built,
/// a bar of them on a terminal, and a stop at the next one once Ctrl-C came under the
/// command's InterruptGuard. A mesh the colliders refuse is an Error naming the file and the
/// mesh's vertex or triangle, checked before the mesh is cut (as `info` checks it).
StaticMap build_mesh_colliders(const std::filesystem::path& mesh, const MeshLoadLimits& limits,
                               double chunk_m, unsigned threads);

/// A generated track's colliders (a chunk each) and plane trees (bake_track_map), with the
/// same bar and stop.
StaticMap build_track_colliders(const Track& track, unsigned threads);

}  // namespace trackphys::cli
