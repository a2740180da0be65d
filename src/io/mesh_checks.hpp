#pragma once

#include <cstddef>
#include <filesystem>
#include <set>
#include <string>
#include <string_view>

#include "io/mesh_format.hpp"

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

void check_ply(std::string_view file);
void check_stl(std::string_view file);
void check_obj(std::string_view file);
void check_off(std::string_view file);
/// Objects nested deeper than max_nesting are refused (MeshLoadLimits::max_nesting).
void check_ac3d(std::string_view file, std::size_t max_nesting);

/// glTF (JSON, binary = false) or GLB (binary = true) in folder, its nodes nested at most
/// max_nesting deep. Returns the external buffer files it refers to (each a
/// relative path inside folder), the only files besides the mesh that assimp may then open
/// (confined_io_system.hpp).
std::set<std::filesystem::path> check_gltf(std::string_view file, bool binary,
                                           const std::filesystem::path& folder,
                                           std::size_t max_nesting);

/// The check of format (one of the above) over a file of folder; returns the external buffers
/// it may refer to (glTF only, else none).
std::set<std::filesystem::path> check_mesh(std::string_view file, MeshFormat format,
                                           const std::filesystem::path& folder,
                                           std::size_t max_nesting);

}  // namespace trackphys::detail
