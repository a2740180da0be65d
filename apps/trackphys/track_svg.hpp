#pragma once

#include <filesystem>
#include <string>

#include "trackphys/track/track.hpp"

namespace trackphys::cli {

/// A top view of track as an SVG document: world x to the right, world z down (the view
/// from above, +Y towards the viewer), the road filled with a colour for its bank angle
/// (blue: right side low, grey: flat, red: left side low), both walls, the start line with
/// the direction of travel, a bank legend, a scale bar and a caption.
std::string track_svg(const Track& track);

/// Writes track_svg(track) to path; throws trackphys::Error if the file cannot be written.
void write_track_svg(const Track& track, const std::filesystem::path& path);

}  // namespace trackphys::cli
