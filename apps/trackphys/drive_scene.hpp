#pragma once

#include <filesystem>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "trackphys/collision/mid_phase_mode.hpp"
#include "trackphys/collision/static_world.hpp"
#include "trackphys/dynamics/car_spec.hpp"
#include "trackphys/dynamics/rigid_body.hpp"
#include "trackphys/io/mesh_load_limits.hpp"
#include "trackphys/track/track.hpp"
#include "trackphys/world/surface.hpp"

namespace trackphys::cli {

/// Where `trackphys drive` drives: a generated track (with its centreline, for the
/// autopilot) or any mesh file (free mode), as static colliders.
struct DriveScene {
    std::optional<Track> track;  ///< set for a generated track
    std::shared_ptr<const StaticWorld> statics;
    ColliderPlaneTrees plane_trees;  ///< a map's or a mesh's (baked); empty: the World builds them
    std::size_t triangle_count = 0;
    std::string description;  ///< for the report
};

/// The generated track of that seed, one collider per chunk.
DriveScene make_track_scene(std::uint64_t seed);
/// A mesh file (any format load_mesh reads, within limits) as `bake` would bake it with its
/// default --chunk: a collider and its plane tree for each 100 m cell, built on every core
/// (build_mesh_colliders), so that the drive is the one on that map.
DriveScene make_mesh_scene(const std::filesystem::path& mesh,
                           const MeshLoadLimits& limits = MeshLoadLimits{});
/// A baked map (trackphys bake): its colliders and plane trees, and its track when it was
/// baked from one.
DriveScene make_map_scene(const std::filesystem::path& map);

/// The World's surface table for a scenario's grips (Scenario::surfaces) on the scene: the
/// grips by surface id, then the dry road (grip 1) for every id of its triangles past them,
/// so that a scenario lists only the surfaces up to the last it changes. Empty for none.
std::vector<Surface> surface_table(const DriveScene& scene, std::span<const Surface> grips);

/// The grips as the reports show them after the scene: ", surface grips 1, 0.25", or
/// nothing for none.
std::string describe_grips(std::span<const Surface> grips);

/// The car at rest on the track's start line, facing along the track.
RigidBodyState start_on_track(const Track& track, const CarSpec& car);

/// The car upright, facing `heading_deg` (about +Y, counter-clockwise from above, 0 = +X,
/// 90 = -Z), its centre of mass straight above or below `spawn`, resting on the surface
/// (place_car_on_surface). Throws trackphys::Error, naming the spawn point, when nothing is
/// below it or the car does not fit there.
RigidBodyState spawn_on_surface(const StaticWorld& statics, const CarSpec& car,
                                const glm::dvec3& spawn, double heading_deg);

}  // namespace trackphys::cli
