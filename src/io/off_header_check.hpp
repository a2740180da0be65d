#pragma once

#include <cstdint>
#include <istream>
#include <optional>
#include <string>

namespace trackphys::detail {

/// Why assimp 5.2.5 must not be given this stream's file as OFF, or nullopt when it may.
/// assimp's OFF reader allocates the vertex and face counts of the header line before it
/// reads a vertex: "OFF" followed by thirty digits makes it ask for tens of gigabytes (found
/// by fuzz_mesh_import). Counts are read as assimp reads them (decimal digits wrapping at
/// 2^32); a count of more vertices or faces than the file has bytes (each takes a line) is
/// refused. `any_header`: also parse a file without the "OFF" keyword (a headerless OFF
/// file, which assimp reads under the .off extension); otherwise such a file is no concern.
/// file_size: the stream's size in bytes. Reads the first 64 KB at most.
std::optional<std::string> off_header_problem(std::istream& in, std::uintmax_t file_size,
                                              bool any_header);

}  // namespace trackphys::detail
