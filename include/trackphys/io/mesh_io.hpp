#pragma once

#include <cstddef>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "trackphys/export.hpp"
#include "trackphys/geometry/aabb.hpp"
#include "trackphys/geometry/triangle_mesh.hpp"
#include "trackphys/io/mesh_load_limits.hpp"

/// Mesh files in and out, through assimp.
///
/// Precision: assimp (as packaged by Debian) stores positions and node transforms in float32,
/// so every coordinate read or written rounds through float32 (24-bit mantissa): about 0.5 mm
/// at 5 km from the origin, 1e-7 relative. Import converts to double before composing the node
/// transforms and applying them, so no further error accumulates beyond that of the file.
/// Export rounds each double coordinate to the nearest float32; coordinates that float32
/// represents exactly (small integers, multiples of powers of two) round-trip exactly.

namespace trackphys {

/// What load_mesh found in a file besides the mesh itself. Counts are over mesh instances:
/// a mesh that two nodes of the file place twice counts twice.
struct MeshLoadReport {
    std::size_t mesh_instances = 0;      ///< meshes merged, one per (node, mesh) reference
    std::size_t triangles = 0;           ///< triangles kept: the result's triangles.size()
    std::size_t vertices = 0;            ///< vertices kept: the result's vertices.size()
    std::size_t degenerate_dropped = 0;  ///< zero or near-zero area (Triangle::is_degenerate)
    /// Triangles with the corners of one kept before, in any order (the back face of a
    /// double-sided export): both sides of a triangle collide, so a copy is only work.
    std::size_t duplicates_dropped = 0;
    std::size_t points_skipped = 0;  ///< point primitives (not collision geometry)
    std::size_t lines_skipped = 0;   ///< line primitives (not collision geometry)
    /// Triangles that assimp's polygon triangulation should have produced but did not: it
    /// gives up on polygons it cannot ear-clip (self-intersecting, or collinear runs), and
    /// this is the only trace of that loss.
    std::size_t triangulation_lost = 0;
    /// Mesh instances placed by a mirroring node transform (negative determinant); their
    /// triangles were re-wound so that their normals keep facing the same side of the
    /// surface, as glTF specifies.
    std::size_t mirrored_instances = 0;
    /// The file's material names as assimp lists them (its index order, which may include a
    /// default material assimp adds, e.g. "DefaultMaterial"), up to the last one a mesh of
    /// the file uses: surface id k of the mesh is materials[k], so a game builds its
    /// WorldSettings::surfaces by these names.
    std::vector<std::string> materials;
    Aabb bounds;        ///< world box of the kept triangles (m)
    double area = 0.0;  ///< total area of the kept triangles (m^2)
};

/// Hears how far load_mesh has placed the file's triangles: `done` of `total`, the triangles
/// its nodes place, counted before degenerate and duplicate ones are dropped. Called once
/// when the file is read and placing begins (done 0), every 65,536 triangles and at the end
/// (done == total; once only when total is 0), with done rising. Nothing is heard while
/// the file is checked and read, before placing. What it throws stops the load and comes out
/// of load_mesh as it was, which is how a caller cancels one.
using MeshLoadProgress = std::function<void(std::size_t done, std::size_t total)>;

/// Reads an OBJ, PLY, STL, glTF/GLB, AC3D or OFF file (by its extension: .obj, .ply, .stl,
/// .gltf, .glb, .ac/.acc/.ac3d, .off, any case) into one triangle mesh in world space
/// (metres, +Y up, coordinates as written in the file; no axis conversion). Every mesh of
/// the file is placed by its nodes' composed transforms and merged; polygons are
/// triangulated; points and lines are skipped; degenerate triangles are dropped; vertices
/// with bit-identical world positions are welded into one and vertices no kept triangle uses
/// are left out; a triangle whose welded corners are those of one kept before (in any order,
/// so either winding) is dropped, the first kept with its winding and surface. All of this
/// is counted in report. Each triangle's surface id
/// (TriangleMesh::surfaces) is the index of its mesh's material among the file's
/// (report.materials names them): a file with one material gives every triangle surface 0.
///
/// Throws trackphys::Error, with a message naming the file, when the file is missing,
/// unreadable, empty, of another format, malformed or truncated (the message names the line
/// or byte: docs/design.md#input-and-output); when a vertex coordinate or node transform is
/// NaN or infinite (the message also names the mesh or node and the vertex, e.g. "mesh
/// 'road', vertex 17 has a non-finite coordinate (0, nan, 1)"; vertices are numbered as
/// assimp numbers them within the mesh, which for OBJ counts face corners, not `v` lines);
/// or when no triangle is left.
///
/// Bounded: the whole file is checked before assimp reads it (every count against the bytes
/// that hold it, every index in range, nesting at most limits.max_nesting deep), so a hostile
/// file is refused in time linear in its size and allocates at most a small multiple of it.
/// The file is read once: the check and assimp see the same bytes. No file but the
/// mesh and, for glTF, the buffers it names inside its own folder is ever opened: no
/// absolute path, `..`, URL or material file.
///
/// Limits (mesh_load_limits.hpp): a file beyond one throws trackphys::Error naming the file
/// and the limit, e.g. "mesh file 'a.obj': more than 1000 triangles, the limit
/// max_triangles". Bytes and nesting are checked before assimp reads the file; triangles and
/// vertices as the mesh is assembled, so it never holds more. A limit of 0, or max_nesting
/// above max_mesh_nesting_allowed, throws before the file is opened.
///
/// `progress`, when given, hears of the triangles placed (a file of millions of triangles
/// takes seconds, most of them placing: welding, dropping and checking each triangle).
TRACKPHYS_API TriangleMesh load_mesh(const std::filesystem::path& path, MeshLoadReport& report,
                                     const MeshLoadLimits& limits = MeshLoadLimits{},
                                     const MeshLoadProgress& progress = {});

/// load_mesh without the report.
TRACKPHYS_API TriangleMesh load_mesh(const std::filesystem::path& path,
                                     const MeshLoadLimits& limits = MeshLoadLimits{});

/// Writes mesh (world space, one node) in the format named by the extension,
/// case-insensitive: .glb (binary glTF 2), .gltf (glTF 2 JSON with its buffer in a .bin file
/// of the same stem beside it), .obj (Wavefront, no material file), .ply (binary PLY), .stl
/// (binary STL, unindexed). Positions are stored as float32 in every one of them (see the
/// precision note above). Surface ids (TriangleMesh::surfaces) are kept by glTF alone, for
/// a mesh whose ids 0 to the highest all have triangles (as the generated track's road 0
/// and walls 1): it is written as one material per id ("surface 0", "surface 1", ...) and one
/// mesh of each id's triangles, so that load_mesh gives each triangle its id again. The
/// other formats, and glTF for any other mesh (one surface, or an id without triangles
/// below the highest, which glTF's unused material would not keep), hold one mesh with
/// assimp's default material, in triangle order: every id 0 when read back.
/// Throws also for a surface list that is neither empty nor one id per triangle.
///
/// The files are first written into a fresh temporary folder beside the destination and
/// then renamed into place, so a failure never leaves a partial file and never disturbs an
/// existing file of that name. Throws trackphys::Error naming the path when the extension is
/// unknown, the mesh is invalid (no triangles, an index out of range, a non-finite
/// coordinate or one beyond float32's range), or writing fails.
TRACKPHYS_API void save_mesh(const TriangleMesh& mesh, const std::filesystem::path& path);

/// The extensions save_mesh writes, for messages: ".glb, .gltf, .obj, .ply or .stl".
inline constexpr const char* saved_mesh_extensions = ".glb, .gltf, .obj, .ply or .stl";

/// True when save_mesh knows the format of path's extension (a check to run before long
/// work whose result would go there).
TRACKPHYS_API bool can_save_mesh_as(const std::filesystem::path& path);

}  // namespace trackphys
