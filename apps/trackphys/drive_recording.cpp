#include "drive_recording.hpp"

#include <cstdint>
#include <string>
#include <system_error>

#include <nlohmann/json.hpp>

#include "track_mesh.hpp"
#include "trackphys/collision/static_collider.hpp"
#include "trackphys/error.hpp"
#include "trackphys/io/mesh_io.hpp"

namespace trackphys::cli {

std::filesystem::path recording_track_mesh_file(const std::filesystem::path& record) {
    const std::string name = record.stem().string() + ".track.glb";
    try {
        (void)nlohmann::json(name).dump();  // throws on bytes that are not UTF-8
    } catch (const nlohmann::json::type_error&) {
        throw Error("--record " + quoted_text(record.string()) +
                    ": the file name is not UTF-8, and the recording names its track in JSON "
                    "by it (rename the file)");
    }
    return std::filesystem::absolute(record).parent_path() / name;
}

namespace {

// The track as driven: a generated track's chunks as `track --out` writes them, else every
// triangle the colliders kept (a mesh file's or a baked map's), each with its own vertices.
TriangleMesh scene_mesh(const DriveScene& scene) {
    if (scene.track) return merge_chunks(*scene.track);
    TriangleMesh mesh;
    for (std::uint32_t id = 0; id < scene.statics->size(); ++id) {
        const StaticCollider& collider = scene.statics->collider(id);
        for (std::uint32_t t = 0; t < collider.mesh_triangle_count(); ++t) {
            if (!collider.has_triangle(t)) continue;
            const auto first = static_cast<std::uint32_t>(mesh.vertices.size());
            for (const glm::dvec3& v : collider.triangle(t).vertices) mesh.vertices.push_back(v);
            mesh.triangles.push_back({first, first + 1, first + 2});
        }
    }
    return mesh;
}

}  // namespace

DriveRecordingPlan plan_drive_recording(const std::filesystem::path& record,
                                        const DriveScene& scene, const CarSpec& car, double dt,
                                        std::size_t cars) {
    DriveRecordingPlan plan;
    plan.header.dt = dt;
    plan.header.scene = scene.description;
    plan.header.car_ellipsoids.assign(cars, car.ellipsoids);
    plan.track_mesh_file = recording_track_mesh_file(record);
    plan.header.track_mesh = plan.track_mesh_file.filename();
    return plan;
}

void commit_with_track_mesh(StagedOutputs& outputs, const DriveRecordingPlan& plan,
                            const DriveScene& scene) {
    if (!plan.track_mesh_file.empty()) save_mesh(scene_mesh(scene), plan.track_mesh_file);
    try {
        outputs.commit();
    } catch (const Error&) {
        std::error_code ignored;
        if (!plan.track_mesh_file.empty()) std::filesystem::remove(plan.track_mesh_file, ignored);
        throw;
    }
}

}  // namespace trackphys::cli
