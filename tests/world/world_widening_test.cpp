// A car thrown out of its update box mid-update (World widens the box and begins a new
// mid-phase update): every ellipsoid's list must come from the new update. In the none and
// per_update_tree modes the new update refills the storage the lists point into, so a list
// kept from before the widening culls against other triangles' frames (or freed memory).
#include <cmath>
#include <cstdint>
#include <memory>
#include <numbers>
#include <string>

#include <gtest/gtest.h>

#include <glm/gtc/quaternion.hpp>

#include "trackphys/collision/mid_phase.hpp"
#include "trackphys/world/world.hpp"
#include "world/update_box.hpp"
#include "world/world_scenes.hpp"

namespace trackphys {
namespace {

// Ground of 0.25 m cells, gently rolling, so that neighbouring triangles have frames of
// their own and a wider box holds many more of them.
std::shared_ptr<const StaticWorld> rolling_ground() {
    TriangleMesh mesh = test::flat_grid(-10.0, 10.0, -12.0, 28.0, 80, 160);
    for (glm::dvec3& v : mesh.vertices) v.y = 0.02 * std::sin(1.3 * v.x) * std::cos(0.9 * v.z);
    return test::static_world_of(mesh);
}

RigidBodyState standing(const glm::dvec3& position, double heading, double speed) {
    RigidBodyState state;
    state.position = position;
    state.orientation = glm::angleAxis(heading, glm::dvec3(0.0, 1.0, 0.0));
    state.linear_velocity = state.orientation * glm::dvec3(0.0, 0.0, speed);
    return state;
}

// A car at 250 km/h into the side of a standing one, which the impact throws sideways far
// beyond its update box. Returns the cars' state hash after the impact, and counts the
// updates in which a box was widened.
std::uint64_t side_impact(MidPhaseMode mode, int& widenings) {
    WorldSettings settings;
    settings.mid_phase = mode;
    settings.threads = 1;
    const std::shared_ptr<const StaticWorld> statics = rolling_ground();
    World world(statics, settings);
    const CarSpec spec = CarSpec::default_car();
    const double ride = spec.lowest_point_depth() + 0.03;
    world.add_car(spec, standing({0.0, ride, 0.0}, 0.5 * std::numbers::pi, 0.0));
    world.add_car(spec, standing({0.0, ride, -7.0}, 0.0, 250.0 / 3.6));

    // In these modes the profile counts each begin_update's broad-phase candidates: more
    // than the update boxes hold means a box was widened.
    MidPhase probe(MidPhaseMode::none, *statics);
    widenings = 0;
    for (int update = 0; update < 60; ++update) {
        std::uint64_t in_boxes = 0;
        for (std::size_t i = 0; i < world.car_count(); ++i) {
            probe.begin_update(detail::car_update_box(world.car(i), settings));
            in_boxes += probe.broad_phase_candidate_count();
        }
        world.update();
        if (mode != MidPhaseMode::precomputed_tree && world.last_profile().candidates > in_boxes)
            ++widenings;
    }
    return world.state_hash();
}

class WorldWidening : public testing::TestWithParam<MidPhaseMode> {};

// The trees' candidates outlive a growing box, so precomputed_tree is the reference; the
// three modes list the same triangles for each shape, and the deepest contact does not
// depend on their order.
TEST_P(WorldWidening, ListsEveryEllipsoidAgainFromTheWiderBox) {
    int widenings = 0;
    const std::uint64_t hash = side_impact(GetParam(), widenings);
    EXPECT_GT(widenings, 0) << "the impact never widened an update box";
    int unused = 0;
    EXPECT_EQ(hash, side_impact(MidPhaseMode::precomputed_tree, unused));
}

INSTANTIATE_TEST_SUITE_P(World, WorldWidening,
                         testing::Values(MidPhaseMode::none, MidPhaseMode::per_update_tree),
                         [](const testing::TestParamInfo<MidPhaseMode>& instance) {
                             return std::string(to_string(instance.param));
                         });

}  // namespace
}  // namespace trackphys
