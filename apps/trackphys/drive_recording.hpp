#pragma once

#include <cstddef>
#include <filesystem>

#include "drive_scene.hpp"
#include "staged_outputs.hpp"
#include "trackphys/dynamics/car_spec.hpp"
#include "trackphys/io/recording.hpp"

namespace trackphys::cli {

/// What `drive --record FILE` and `race --record FILE` write: the recording's header and
/// the track mesh driven on, beside the recording (recording_track_mesh_file), which the
/// header names by its file name, so that the two move together and `view` reads nothing
/// outside the recording's folder.
struct DriveRecordingPlan {
    RecordingHeader header;
    std::filesystem::path track_mesh_file;  ///< to write
};

/// The track mesh that `--record record` writes beside the recording: its folder, its stem
/// + ".track.glb". Throws trackphys::Error when that name is not UTF-8: the header names the
/// track in JSON, which could hold only a replacement naming no file, and the recording
/// could not be viewed.
std::filesystem::path recording_track_mesh_file(const std::filesystem::path& record);

/// `cars` cars of one spec (drive: 1; race: the field).
DriveRecordingPlan plan_drive_recording(const std::filesystem::path& record,
                                        const DriveScene& scene, const CarSpec& car, double dt,
                                        std::size_t cars = 1);

/// Writes the plan's track mesh, if any, then puts the staged outputs in place; removes the
/// mesh again if they cannot be (save_mesh is atomic itself), as `trackphys track` does
/// with its mesh. Call it last, after every staged output is written.
void commit_with_track_mesh(StagedOutputs& outputs, const DriveRecordingPlan& plan,
                            const DriveScene& scene);

}  // namespace trackphys::cli
