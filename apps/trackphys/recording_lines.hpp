#pragma once

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace trackphys::cli {

/// What a recording's header says, once its lines are checked.
struct RecordingLines {
    std::size_t cars = 0;
    std::optional<std::string> track_mesh;  ///< the header's track.mesh, as written
};

/// Checks a recording's text (docs/recording.md) as the viewer reads it
/// (viewer/src/recording.ts), so that `trackphys view` refuses what the page would refuse
/// rather than write a page that shows only the refusal: the header (format, version 1 or 2,
/// a finite dt, cars a whole number >= 1, version 2's car_ellipsoids for every car and
/// track.mesh a string), at least one frame, and every frame a JSON object whose t is finite
/// and increasing and whose cars are the header's (each car's "s", when given, one value an
/// ellipsoid of a version 2 header), and whose car_contacts, when given, name the header's
/// cars and their ellipsoids. A frame's other values are the page's to check. Throws
/// trackphys::Error naming `path` and the line.
RecordingLines check_recording_lines(std::string_view text, const std::filesystem::path& path);

}  // namespace trackphys::cli
