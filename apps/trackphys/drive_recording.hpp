#pragma once

#include <cstddef>
#include <filesystem>

#include "drive_scene.hpp"
#include "staged_outputs.hpp"
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

/// `cars` cars of one spec (drive: 1; race: the field).
DriveRecordingPlan plan_drive_recording(const std::filesystem::path& record,
                                        const DriveScene& scene,
                                        const std::filesystem::path& mesh_file, const CarSpec& car,
                                        double dt, std::size_t cars = 1);

/// Writes the plan's track mesh, if any, then puts the staged outputs in place; removes the
/// mesh again if they cannot be (save_mesh is atomic itself), as `trackphys track` does
/// with its mesh. Call it last, after every staged output is written.
void commit_with_track_mesh(StagedOutputs& outputs, const DriveRecordingPlan& plan,
                            const DriveScene& scene);

}  // namespace trackphys::cli
