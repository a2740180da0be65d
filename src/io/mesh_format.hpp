#pragma once

#include <filesystem>
#include <optional>
#include <string>

namespace trackphys::detail {

/// The mesh formats load_mesh reads: those a strict check of our own bounds before assimp's
/// reader sees the file (docs/design.md#input-and-output). Any other extension is refused,
/// since assimp's other readers allocate, recurse and loop on what a hostile file claims.
enum class MeshFormat { obj, ply, stl, gltf, glb, ac3d, off };

/// The format of path's extension (case-insensitive), or nullopt when trackphys does not read
/// it.
std::optional<MeshFormat> mesh_format_of(const std::filesystem::path& path);

/// The extensions load_mesh reads, for messages: ".obj, .ply, ...".
std::string read_mesh_extensions();

/// The name (aiImporterDesc::mName) of the one assimp reader that may see a file of this
/// format: no other is registered, so assimp cannot fall back to guessing by content.
const char* assimp_reader_name(MeshFormat format);

}  // namespace trackphys::detail
