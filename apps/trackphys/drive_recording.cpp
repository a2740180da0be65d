#include "drive_recording.hpp"

#include <system_error>

#include "track_mesh.hpp"
#include "trackphys/error.hpp"
#include "trackphys/io/mesh_io.hpp"

namespace trackphys::cli {

DriveRecordingPlan plan_drive_recording(const std::filesystem::path& record,
                                        const DriveScene& scene,
                                        const std::filesystem::path& mesh_file, const CarSpec& car,
                                        double dt, std::size_t cars) {
    namespace fs = std::filesystem;
    DriveRecordingPlan plan;
    plan.header.dt = dt;
    plan.header.scene = scene.description;
    plan.header.car_ellipsoids.assign(cars, car.ellipsoids);
    const fs::path folder = fs::absolute(record).parent_path();
    if (scene.track) {
        plan.track_mesh_file = folder / (record.stem().string() + ".track.glb");
        plan.header.track_mesh = plan.track_mesh_file.filename();
    } else {
        // Relative, so that the recording and the mesh can move together.
        plan.header.track_mesh = fs::absolute(mesh_file).lexically_relative(folder);
    }
    return plan;
}

void commit_with_track_mesh(StagedOutputs& outputs, const DriveRecordingPlan& plan,
                            const DriveScene& scene) {
    if (!plan.track_mesh_file.empty()) save_mesh(merge_chunks(*scene.track), plan.track_mesh_file);
    try {
        outputs.commit();
    } catch (const Error&) {
        std::error_code ignored;
        if (!plan.track_mesh_file.empty()) std::filesystem::remove(plan.track_mesh_file, ignored);
        throw;
    }
}

}  // namespace trackphys::cli
