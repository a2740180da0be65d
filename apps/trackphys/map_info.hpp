#pragma once

#include <string>

namespace trackphys::cli {

/// `trackphys info MAP.tpmap`: what a baked map holds (format, build options, colliders,
/// triangles, memory of each structure, its track), as text or one JSON object.
void print_map_info(const std::string& file, bool json);

}  // namespace trackphys::cli
