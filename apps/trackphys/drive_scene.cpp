#include "drive_scene.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>

#include <glm/gtc/quaternion.hpp>

#include "collider_build.hpp"
#include "commands.hpp"
#include "trackphys/error.hpp"
#include "trackphys/geometry/ellipsoid.hpp"
#include "trackphys/io/map_file.hpp"
#include "trackphys/world/spawn.hpp"

namespace trackphys::cli {
namespace {

// The centre of mass's height for the car to start a millimetre clear of the surface and
// settle onto it.
double ride_height(const CarSpec& car) { return car.lowest_point_depth() + 0.001; }

// A baked or loaded map's colliders, plane trees and track (when it has one).
DriveScene scene_of(StaticMap map, std::string description) {
    DriveScene scene;
    scene.track = std::move(map.track);
    for (std::uint32_t id = 0; id < map.statics->size(); ++id)
        scene.triangle_count += map.statics->collider(id).mesh_triangle_count();
    scene.statics = std::move(map.statics);
    scene.plane_trees = std::move(map.plane_trees);
    scene.description = std::move(description);
    return scene;
}

}  // namespace

DriveScene make_track_scene(std::uint64_t seed) {
    TrackParams params;
    params.seed = seed;
    DriveScene scene;
    scene.track = generate_track(params);
    auto statics = std::make_shared<StaticWorld>();
    for (const TrackChunk& chunk : scene.track->chunks) {
        statics->add(std::make_shared<StaticCollider>(chunk.mesh));
        scene.triangle_count += chunk.mesh.triangles.size();
    }
    scene.statics = std::move(statics);
    std::ostringstream what;
    what << "generated track, seed " << seed << ", " << scene.track->length_m << " m";
    scene.description = what.str();
    return scene;
}

DriveScene make_mesh_scene(const std::filesystem::path& mesh, const MeshLoadLimits& limits) {
    return scene_of(build_mesh_colliders(mesh, limits, kDefaultChunkM, 0), "mesh " + mesh.string());
}

DriveScene make_map_scene(const std::filesystem::path& map) {
    return scene_of(load_static_world(map), "map " + map.string());
}

std::vector<Surface> surface_table(const DriveScene& scene, std::span<const Surface> grips) {
    if (grips.empty()) return {};
    std::size_t size = grips.size();
    for (std::uint32_t id = 0; id < scene.statics->size(); ++id)
        size = std::max(size, std::size_t{scene.statics->collider(id).highest_surface()} + 1);
    std::vector<Surface> table(grips.begin(), grips.end());
    table.resize(size);  // Surface{} is the dry road
    return table;
}

std::string describe_grips(std::span<const Surface> grips) {
    std::ostringstream text;
    for (std::size_t id = 0; id < grips.size(); ++id)
        text << (id == 0 ? ", surface grips " : ", ") << grips[id].grip;
    return text.str();
}

RigidBodyState start_on_track(const Track& track, const CarSpec& car) {
    const CenterlineSample& start = track.centerline.front();
    RigidBodyState state;
    state.position = start.position + start.up * ride_height(car);
    // Body axes +X left, +Y up, +Z forward onto the road frame at the start line.
    state.orientation =
        glm::normalize(glm::quat_cast(glm::dmat3(start.left, start.up, start.tangent)));
    return state;
}

RigidBodyState spawn_on_surface(const StaticWorld& statics, const CarSpec& car,
                                const glm::dvec3& spawn, double heading_deg) {
    // Rotating about +Y by a maps body +Z to (sin a, 0, cos a); heading h wants
    // (cos h, 0, -sin h), so a = h + 90 degrees.
    const double a = (heading_deg + 90.0) * std::numbers::pi / 180.0;
    try {
        return place_car_on_surface(statics, car, spawn,
                                    glm::angleAxis(a, glm::dvec3(0.0, 1.0, 0.0)));
    } catch (const Error& e) {
        std::ostringstream why;
        why << "--spawn " << spawn.x << ',' << spawn.y << ',' << spawn.z << ": " << e.what();
        throw Error(why.str());
    }
}

}  // namespace trackphys::cli
