#pragma once

#include <filesystem>
#include <set>
#include <string>
#include <string_view>

namespace trackphys::detail {

/// The strict checks load_mesh runs over a whole file before assimp's reader sees it, one
/// per format (docs/design.md#input-and-output). Each walks the file in time and memory
/// linear in its size and refuses, naming the place (a line, or a byte offset), whatever
/// assimp's reader would allocate for beyond the file's bytes, index out of range, crash or
/// loop on, and whatever it would silently read as a plausible mesh though malformed: a
/// count past 2^32 or with trailing characters, a list count too big for its declared type,
/// an index out of range. A file that passes holds every element it claims, so what assimp
/// allocates for it is bounded by a small multiple of its size.

/// What a check throws: the reason and the place, without the file's name (load_mesh adds it).
struct MeshCheckError {
    std::string reason;
};

/// The deepest nesting of objects or nodes a check lets through (AC3D kids, glTF nodes,
/// glTF JSON): real tracks nest a few levels; assimp's readers recurse once per level.
inline constexpr std::size_t kMaxMeshNesting = 64;

void check_ply(std::string_view file);
void check_stl(std::string_view file);
void check_obj(std::string_view file);
void check_off(std::string_view file);
void check_ac3d(std::string_view file);

/// glTF (JSON, binary = false) or GLB (binary = true) in folder. Returns the external buffer
/// files it refers to (each a relative path inside folder), the only files besides the mesh
/// that assimp may then open (confined_io_system.hpp).
std::set<std::filesystem::path> check_gltf(std::string_view file, bool binary,
                                           const std::filesystem::path& folder);

}  // namespace trackphys::detail
