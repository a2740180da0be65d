#pragma once

// The generated track as a static world, for the tests that drive on it.

#include <cstdint>
#include <memory>

#include <glm/gtc/quaternion.hpp>
#include <glm/mat3x3.hpp>

#include "trackphys/collision/mid_phase.hpp"
#include "trackphys/collision/static_world.hpp"
#include "trackphys/dynamics/car_spec.hpp"
#include "trackphys/track/track.hpp"
#include "trackphys/track/track_params.hpp"

namespace trackphys::test {

/// A generated track, its colliders (one per chunk) and their plane trees.
struct TrackWorld {
    Track track;
    std::shared_ptr<const StaticWorld> statics;
    ColliderPlaneTrees trees;  ///< built once, shared by every world of a test
};

inline TrackWorld make_track_world(std::uint64_t seed) {
    TrackParams params;
    params.seed = seed;
    TrackWorld tw{generate_track(params), nullptr, {}};
    auto statics = std::make_shared<StaticWorld>();
    for (const TrackChunk& chunk : tw.track.chunks)
        statics->add(std::make_shared<StaticCollider>(chunk.mesh));
    tw.statics = std::move(statics);
    tw.trees = make_collider_plane_trees(*tw.statics);
    return tw;
}

/// The default track (seed 7), built once per test process.
inline const TrackWorld& default_track() {
    static const TrackWorld instance = make_track_world(7);
    return instance;
}

/// The default car at rest on the start line, a millimetre above the road.
inline RigidBodyState on_start_line(const Track& track) {
    const CenterlineSample& s = track.centerline.front();
    RigidBodyState state;
    state.position = s.position + s.up * (CarSpec::default_car().lowest_point_depth() + 0.001);
    state.orientation = glm::normalize(glm::quat_cast(glm::dmat3(s.left, s.up, s.tangent)));
    return state;
}

}  // namespace trackphys::test
