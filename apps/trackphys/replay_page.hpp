#pragma once

#include <filesystem>
#include <string>
#include <string_view>

#include "trackphys/io/mesh_load_limits.hpp"

namespace trackphys::cli {

/// What went into a replay page, for the command's report.
struct ReplayPageStats {
    std::size_t recording_bytes = 0;  ///< the recording file
    std::size_t track_triangles = 0;  ///< 0 when the recording has no track
    std::size_t page_bytes = 0;
};

/// A recording as `trackphys view` reads it: checked as the viewer reads it
/// (check_recording_lines), and the track mesh its header names.
struct ReplayRecording {
    std::filesystem::path file;
    std::string text;
    std::filesystem::path track_file;  ///< in file's folder; empty when it has no track
};

/// Reads and checks the recording. Throws trackphys::Error, naming the first bad line, when
/// check_recording_lines refuses it, or when its track is not a plain file name (no folder,
/// not absolute) or is a symbolic link out of the recording's folder: a recording names the
/// track that `drive --record` wrote beside it, and a page must not embed whatever file a
/// recording points to.
ReplayRecording read_replay_recording(const std::filesystem::path& file);

/// One self-contained HTML page that replays the recording: the viewer bundle, the
/// recording and its track mesh inside it, zlib-compressed and base64-encoded
/// (docs/viewer.md, "The page"). The viewer reports a malformed frame's values on the page,
/// naming its line. Throws trackphys::Error when the track cannot be read within
/// mesh_limits.
std::string make_replay_page(const ReplayRecording& recording, std::string_view bundle,
                             const MeshLoadLimits& mesh_limits, ReplayPageStats& stats);

}  // namespace trackphys::cli
