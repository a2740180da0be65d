#pragma once

#include <cstdint>
#include <istream>
#include <optional>
#include <string>

namespace trackphys::detail {

/// Why assimp 5.2.5 must not be given this stream's file, or nullopt when it may. Checks
/// only files that start with PLY's magic ("ply", any case): assimp's PLY reader takes them
/// by content whatever their extension when the extension's own reader declines them (.gltf,
/// .glb, unknown ones), and then
/// - loops forever when no header line is "end_header" (leading blanks allowed), or
///   sometimes when that line ends the file (such a file holds no data: refused too), and
/// - allocates what an element's count claims before it reads a single instance (a 100-byte
///   file claiming 1e11 vertices asks for 1.2 TB), so an element with properties that
///   claims more instances than the file has bytes (each instance takes at least one) is
///   refused.
/// file_size: the stream's size in bytes. Reads the header only (up to end_header).
std::optional<std::string> ply_header_problem(std::istream& in, std::uintmax_t file_size);

}  // namespace trackphys::detail
