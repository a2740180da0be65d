#pragma once

// The benchmarks' shared scene: the default track (seed 7), its tightest banked turn, and
// the default car driving through it at 1000 km/h for one update (40 sub-steps of 0.25 ms,
// 7 cm each, in 10 steps of 4), its wheels on the road.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/gtc/quaternion.hpp>
#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include "trackphys/dynamics/car_spec.hpp"
#include "trackphys/geometry/aabb.hpp"
#include "trackphys/geometry/ellipsoid.hpp"
#include "trackphys/geometry/triangle.hpp"
#include "trackphys/geometry/triangle_mesh.hpp"
#include "trackphys/track/track.hpp"
#include "trackphys/track/track_stats.hpp"

namespace trackphys::bench {

/// Every chunk of a track as one mesh (the chunks' vertices concatenated), for the structures
/// that take a single mesh: brute force, Bullet's btBvhTriangleMeshShape.
TriangleMesh merged_track_mesh(const Track& track);

/// A sphere (m): an ellipsoid's bounding sphere at one sub-step, the cull's query.
struct BoundingSphere {
    glm::dvec3 center;
    double radius;
};

struct TightestTurnScene {
    static constexpr int kSubsteps = 40;     ///< one 10 ms update
    static constexpr int kStepSubsteps = 4;  ///< sub-steps per step (10 steps)
    static constexpr double kSpeed = 1000.0 / 3.6;
    static constexpr double kSubstepDt = 0.01 / kSubsteps;
    /// Height of the centre of mass above the road (m): the car's lowest point (its wheels,
    /// at full droop) 1 cm into the road, as a loaded tyre sits.
    double ride_height = 0.0;

    Track track;
    CenterlineSample turn;
    Aabb update_box;  ///< car_update_box(turn): the broad-phase box of the update
    CarSpec car = CarSpec::default_car();
    glm::dquat car_orientation{1.0, 0.0, 0.0, 0.0};  ///< world from body

    TightestTurnScene();

    /// World center of ellipsoid `e` at the start of sub-step `substep` (0..kSubsteps).
    glm::dvec3 center(std::size_t e, int substep) const {
        const CarEllipsoid& ce = car.ellipsoids[e];
        const glm::dvec3 origin =
            turn.position + turn.tangent * (kSpeed * kSubstepDt * substep) + turn.up * ride_height;
        return origin + turn.left * ce.center.x + turn.up * ce.center.y +
               turn.tangent * ce.center.z;
    }
    /// Ellipsoid `e` at the start of sub-step `substep`.
    Ellipsoid ellipsoid(std::size_t e, int substep) const {
        const CarEllipsoid& ce = car.ellipsoids[e];
        return Ellipsoid(center(e, substep), car_orientation * ce.orientation, ce.semi_axes);
    }
    /// Radius of ellipsoid e's bounding sphere (m).
    double bounding_radius(std::size_t e) const {
        const glm::dvec3& a = car.ellipsoids[e].semi_axes;
        return std::max({a.x, a.y, a.z});
    }

    /// The cull's queries over the update: each sub-step's 8 bounding spheres (40 x 8).
    std::vector<BoundingSphere> bounding_spheres() const;

    /// The broad-phase candidates: every triangle whose box meets the update box.
    std::vector<Triangle> candidates() const;
};

/// Built once per benchmark program (generating the track takes ~0.1 s).
const TightestTurnScene& tightest_turn_scene();

}  // namespace trackphys::bench
