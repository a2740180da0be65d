#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "trackphys/track/track.hpp"

namespace trackphys::cli {

/// One car's path: its position after each update (m) and its speed then (km/h).
struct PlotPath {
    std::vector<glm::dvec3> points;
    std::vector<double> speed_kmh;
};

/// What a drive's or a race's picture shows: every car's path (one point per update, with
/// its speed) and the time every update took.
struct DrivePlot {
    std::string command = "drive";  ///< the picture's title: "trackphys <command>: ..."
    std::vector<PlotPath> paths;    ///< one per car
    std::vector<double> update_us;  ///< wall-clock time of each update
    double dt = 0.01;               ///< simulated seconds per update
};

/// Writes an SVG with two panels: the top view of the paths coloured by speed, over the
/// track's road edges when there is a track (long paths drawn through every few points,
/// so that a race's picture stays a few megabytes); and update time against simulated time with
/// its median and p99. Throws trackphys::Error when the file cannot be written.
void write_drive_svg(const DrivePlot& plot, const std::optional<Track>& track,
                     const std::filesystem::path& path);

}  // namespace trackphys::cli
