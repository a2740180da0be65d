#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "trackphys/collision/mid_phase_mode.hpp"
#include "trackphys/collision/plane_tree.hpp"
#include "trackphys/collision/static_world.hpp"
#include "trackphys/export.hpp"
#include "trackphys/geometry/triangle_mesh.hpp"
#include "trackphys/track/track.hpp"

/// Baked maps (.tpmap, docs/tpmap.md): a static world with every collider's BVH and plane
/// tree already built, written once by `trackphys bake` and loaded without rebuilding
/// anything.

namespace trackphys {

/// The map format this build writes and the only one it reads.
inline constexpr std::uint32_t kMapFormatVersion = 4;

/// A static world ready to drive on: what a map file holds.
struct StaticMap {
    std::shared_ptr<const StaticWorld> statics;
    /// One precomputed plane tree per collider, in id order (World's `trees` argument).
    ColliderPlaneTrees plane_trees;
    /// The build options the plane trees were made with (a World's default is
    /// PlaneTreeSettings::precomputed()).
    PlaneTreeSettings plane_tree_settings = PlaneTreeSettings::precomputed();
    /// For a map baked from a generated track: the track without its chunk meshes (`chunks`
    /// is empty; the colliders are in `statics`), i.e. its parameters, length and centreline,
    /// which the autopilot and the start line need. Empty for a map baked from a mesh.
    std::optional<Track> track;
};

/// Told how far a bake is: `done` of `total` colliders built. Called once per collider,
/// `done` rising by one each time, from whichever thread built it, never two calls at once.
/// What it throws stops the bake, which is how a caller cancels one: no collider is begun
/// after it, and it comes out of bake_map, as it was, once the colliders under way are built
/// (unless a collider of lower index threw too, a refused mesh: the lowest one's comes out).
using BakeProgress = std::function<void(std::size_t done, std::size_t total)>;

/// Builds a map with one collider per mesh, in order, and each collider's plane tree with
/// `settings`, on up to `threads` threads (0: std::thread::hardware_concurrency()), a tree on
/// several when there are fewer meshes than threads. The result does not depend on the
/// thread count. Its trees keep their frames when the meshes'
/// triangles fit kPlaneTreeFrameBudget, as a World's own trees and a loaded map's do
/// (plane_tree_frames_within), and build them in their queries otherwise; a map file stores
/// no frames either way.
/// `progress`, when given, hears of every collider built (a bake of millions of triangles
/// takes tens of seconds). Throws a StaticCollider's trackphys::Error when it refuses a
/// mesh, prefixed "mesh i: " when there are several.
TRACKPHYS_API StaticMap
bake_map(std::span<const TriangleMesh> meshes,
         const PlaneTreeSettings& settings = PlaneTreeSettings::precomputed(), unsigned threads = 0,
         const BakeProgress& progress = {});

/// bake_map over a generated track's chunks (one collider per chunk, as a World built from
/// the track gets), keeping the track (without its chunks) in the map.
TRACKPHYS_API StaticMap bake_track_map(
    const Track& track, const PlaneTreeSettings& settings = PlaneTreeSettings::precomputed(),
    unsigned threads = 0, const BakeProgress& progress = {});

/// The map file's bytes (layout in docs/tpmap.md): a 64-byte header (magic, format version,
/// body length, checksum, plane-tree build options), then the body: records and raw arrays,
/// each padded to 64 bytes, little-endian. Throws trackphys::Error for a map without a
/// static world or without one plane tree per collider.
TRACKPHYS_API std::string encode_map(const StaticMap& map);

/// Reads encode_map's bytes back. `source` names them in messages ("map 'oval.tpmap'").
/// Throws trackphys::Error naming the source and the problem: a wrong magic, another format
/// version, a length or checksum that does not match, plane trees baked with settings other
/// than `expected` (nullopt accepts any), a truncated or inconsistent body, or any array
/// whose contents break the structure's invariants (an index or range out of bounds, a
/// cycle, a tree too deep, a coordinate not finite): the structure is verified once, in
/// time linear in its size, so that no query on a loaded map can read out of bounds or
/// loop. Nothing is ever half-loaded. The colliders are copied and verified on up to
/// `threads` threads (0: std::thread::hardware_concurrency()); the result, and the error of
/// a bad map, do not depend on the thread count. The plane trees keep their frames when the
/// map's fit in `frame_budget_bytes` (plane_tree_frames_within; built on load, not stored).
TRACKPHYS_API StaticMap
decode_map(std::string_view bytes, const std::string& source = "map",
           const std::optional<PlaneTreeSettings>& expected = PlaneTreeSettings::precomputed(),
           unsigned threads = 0, std::size_t frame_budget_bytes = kPlaneTreeFrameBudget);

/// Writes the map file atomically (to a temporary file beside `path`, then renamed over
/// it). Throws trackphys::Error naming the path and the reason.
TRACKPHYS_API void save_map(const std::filesystem::path& path, const StaticMap& map);

/// Reads a map file into memory and decodes it (decode_map, the source named by its path, on
/// up to `threads` threads, frames kept within `frame_budget_bytes`).
TRACKPHYS_API StaticMap load_static_world(
    const std::filesystem::path& path,
    const std::optional<PlaneTreeSettings>& expected = PlaneTreeSettings::precomputed(),
    unsigned threads = 0, std::size_t frame_budget_bytes = kPlaneTreeFrameBudget);

/// True when the file starts with the map magic (any version): what `trackphys info` uses to
/// tell a map from a mesh file. False for a file it cannot read and for anything but a regular
/// file (a FIFO would block the open).
TRACKPHYS_API bool is_map_file(const std::filesystem::path& path);

}  // namespace trackphys
