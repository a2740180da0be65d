// The box a car's update queries the broad phase with: the union of its placed ellipsoids'
// boxes, swept and padded. Each ellipsoid must be placed with its own radii (placing keeps
// the target's radii, so a scratch copy of another ellipsoid would give wrong boxes).
#include "world/update_box.hpp"

#include <cstddef>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

#include "trackphys/collision/static_world.hpp"
#include "trackphys/dynamics/car.hpp"
#include "trackphys/dynamics/car_spec.hpp"
#include "trackphys/world/world_settings.hpp"

namespace trackphys {
namespace {

TEST(UpdateBox, IsTheUnionOfEveryPlacedEllipsoidPadded) {
    const WorldSettings settings;
    const double dt = settings.dt_update;
    const double margin =
        settings.broad_phase_margin + 0.5 * glm::length(settings.gravity) * dt * dt;
    RigidBodyState state;  // at rest: the box is the placed union, padded
    state.position = {12.0, 3.5, -40.0};
    state.orientation = glm::normalize(glm::dquat(0.9, 0.1, -0.35, 0.2));
    const Car car(CarSpec::default_car(), state);

    Aabb placed;
    for (std::size_t i = 0; i < car.ellipsoid_count(); ++i)
        placed.expand(car.world_ellipsoid(i).bounds());
    const Aabb expected = swept_box(placed, glm::dvec3(0.0), margin);
    const Aabb box = detail::car_update_box(car, settings);
    for (int axis = 0; axis < 3; ++axis) {
        EXPECT_EQ(box.min[axis], expected.min[axis]) << "axis " << axis;
        EXPECT_EQ(box.max[axis], expected.max[axis]) << "axis " << axis;
    }
}

}  // namespace
}  // namespace trackphys
