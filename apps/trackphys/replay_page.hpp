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

/// One self-contained HTML page that replays the recording: the viewer bundle, the
/// recording and its track mesh (named in the header, relative to the recording) inside it,
/// zlib-compressed and base64-encoded (docs/viewer.md, "The page"). Only the header is
/// checked here; the viewer reports a malformed frame on the page, naming its line. Throws
/// trackphys::Error when the file is not a trackphys recording or its track cannot be read
/// within mesh_limits.
std::string make_replay_page(const std::filesystem::path& recording, std::string_view bundle,
                             const MeshLoadLimits& mesh_limits, ReplayPageStats& stats);

}  // namespace trackphys::cli
