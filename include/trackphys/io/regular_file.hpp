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

/// Whether `file` lies inside `folder` once symbolic links are followed (both exist): a file
/// that names another beside it (a glTF its buffers, a recording its track) must not reach
/// through a link anything else the user can read.
TRACKPHYS_API bool lies_inside(const std::filesystem::path& file,
                               const std::filesystem::path& folder);

}  // namespace trackphys
