#pragma once

#include <cstddef>
#include <cstdint>

/// How big a mesh file load_mesh accepts (mesh_io.hpp). Whatever the limits, a hostile file
/// cannot make load_mesh allocate much more than its own size (every count is checked against
/// the bytes that hold it before any reader allocates); these limits are the caller's own
/// budget on top of that, for files they do not trust: a server that loads its players'
/// tracks sets them to what it can afford. The defaults refuse no real track: a 50-million-
/// triangle track loads in every format.

namespace trackphys {

struct MeshLoadLimits {
    /// Triangles in the loaded mesh (MeshLoadReport::triangles: after triangulation, once
    /// per placement of an instanced mesh, degenerate ones not counted). A file whose nodes
    /// place more, degenerate ones counted, is refused before any is placed. Twice the 50
    /// million a big track needs; a mesh at this limit holds 1.2 GB of indices, and its load
    /// 2 to 3 GB more for finding duplicate triangles (16 to 32 bytes a triangle).
    std::uint64_t max_triangles = 100'000'000;
    /// Vertices in the loaded mesh (MeshLoadReport::vertices: welded by position). A
    /// connected surface has about half as many vertices as triangles; this lets through
    /// even a 50-million-triangle soup whose triangles share no corner (3 x 50 million).
    std::uint64_t max_vertices = 150'000'000;
    /// Bytes of the mesh file plus, for glTF, the buffer files it names. 16 GiB: an ASCII
    /// STL, the most verbose format, takes about 260 bytes a triangle, 13 GB for 50 million.
    std::uint64_t max_bytes = std::uint64_t{16} << 30;
    /// Corners of one polygon (a face of OBJ, PLY, OFF or AC3D). Triangulating a polygon takes
    /// time growing with the square of its corners, so a small file of a few huge polygons
    /// could hold a core for minutes; no real track's polygon comes near the default.
    std::size_t max_polygon_corners = 1024;
    /// Nesting of AC3D objects and glTF nodes (glTF's JSON has its own fixed limit of 64
    /// levels). Real tracks nest a few levels.
    std::size_t max_nesting = 64;
};

/// The deepest max_nesting load_mesh accepts: assimp's readers recurse once per level, and
/// this keeps their stack well inside a thread's.
inline constexpr std::size_t max_mesh_nesting_allowed = 256;

}  // namespace trackphys
