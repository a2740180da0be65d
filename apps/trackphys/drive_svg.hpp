#pragma once

#include <filesystem>
#include <optional>
#include <vector>

#include <glm/vec3.hpp>

#include "trackphys/track/track.hpp"

namespace trackphys::cli {

/// What a drive's picture shows: the car's path (one point per update, with its speed) and
/// the time every update took.
struct DrivePlot {
    std::vector<glm::dvec3> path;   ///< car position after each update (m)
    std::vector<double> speed_kmh;  ///< speed after each update
    std::vector<double> update_us;  ///< wall-clock time of each update
    double dt = 0.01;               ///< simulated seconds per update
};

/// Writes an SVG with two panels: the top view of the path coloured by speed, over the
/// track's road edges when there is a track; and update time against simulated time with
/// its median and p99. Throws trackphys::Error when the file cannot be written.
void write_drive_svg(const DrivePlot& plot, const std::optional<Track>& track,
                     const std::filesystem::path& path);

}  // namespace trackphys::cli
