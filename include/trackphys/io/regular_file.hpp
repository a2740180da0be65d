#pragma once

#include <filesystem>
#include <string>

#include "trackphys/export.hpp"

namespace trackphys {

/// The check every trackphys file loader makes before it opens a path, so that each refuses
/// alike: a folder, a device or a pipe (/dev/zero, a FIFO) would otherwise fail late with a
/// stream error, block in open() or never end. Throws trackphys::Error "<name>: no such
/// file", "<name>: is a folder, not a file" or "<name>: not a regular file" unless `path`
/// is a regular file (links followed); `name` is how messages name it ("snapshot 'a.snap'").
TRACKPHYS_API void require_regular_file(const std::filesystem::path& path, const std::string& name);

}  // namespace trackphys
