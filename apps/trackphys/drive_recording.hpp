#pragma once

#include <filesystem>

#include "drive_scene.hpp"
#include "trackphys/dynamics/car_spec.hpp"
#include "trackphys/io/recording.hpp"

namespace trackphys::cli {

/// What `drive --record FILE` writes: the recording's header and, for a generated track,
/// the track mesh beside the recording (FILE's stem + ".track.glb"), which the header
/// names; a mesh file driven on is named by its path relative to FILE's folder instead.
struct DriveRecordingPlan {
    RecordingHeader header;
    std::filesystem::path track_mesh_file;  ///< to write, empty when the mesh exists
};

DriveRecordingPlan plan_drive_recording(const std::filesystem::path& record,
                                        const DriveScene& scene,
                                        const std::filesystem::path& mesh_file, const CarSpec& car,
                                        double dt);

}  // namespace trackphys::cli
