#pragma once

#include <cstddef>

#include <glm/geometric.hpp>

#include "trackphys/collision/static_world.hpp"
#include "trackphys/dynamics/car.hpp"
#include "trackphys/geometry/aabb.hpp"
#include "trackphys/geometry/ellipsoid.hpp"
#include "trackphys/world/world_settings.hpp"

namespace trackphys::detail {

/// The box the broad phase queries for a car's update: it covers every triangle the car can
/// touch during it. The union of its ellipsoids' boxes, swept by its velocity over the
/// update and padded by what rotation and a changing velocity can add: any body point moves
/// at most |omega| R dt by rotation, and gravity alone bends the path by |g| dt^2 / 2.
inline Aabb car_update_box(const Car& car, const WorldSettings& settings) {
    // One placing rotation (its matrix and its entries' check) for all the ellipsoids: this
    // runs for every car on one thread, before the islands share the update out.
    const PlacingRotation orientation(car.state().orientation);
    Aabb box;
    for (std::size_t i = 0; i < car.ellipsoid_count(); ++i)
        box.expand(car.world_ellipsoid(i, orientation).bounds());
    const double dt = settings.dt_update;
    const RigidBodyState& state = car.state();
    const double margin = settings.broad_phase_margin +
                          glm::length(state.angular_velocity) * car.bounding_radius() * dt +
                          0.5 * glm::length(settings.gravity) * dt * dt;
    return swept_box(box, state.linear_velocity * dt, margin);
}

}  // namespace trackphys::detail
