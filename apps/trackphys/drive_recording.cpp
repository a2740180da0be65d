#include "drive_recording.hpp"

namespace trackphys::cli {

DriveRecordingPlan plan_drive_recording(const std::filesystem::path& record,
                                        const DriveScene& scene,
                                        const std::filesystem::path& mesh_file, const CarSpec& car,
                                        double dt) {
    namespace fs = std::filesystem;
    DriveRecordingPlan plan;
    plan.header.dt = dt;
    plan.header.scene = scene.description;
    plan.header.car_ellipsoids = {car.ellipsoids};
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

}  // namespace trackphys::cli
