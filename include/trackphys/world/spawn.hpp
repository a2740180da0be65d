#pragma once

#include <glm/gtc/quaternion.hpp>
#include <glm/vec3.hpp>

#include "trackphys/collision/static_world.hpp"
#include "trackphys/dynamics/car_spec.hpp"
#include "trackphys/dynamics/rigid_body.hpp"
#include "trackphys/export.hpp"
#include "trackphys/math/types.hpp"

namespace trackphys {

/// Places a car on the surface of `statics` for World::add_car: the car keeps
/// `orientation` and the x and z of `position` (its centre of mass) and moves only along
/// world +Y, to the height at which it touches: every ellipsoid (wheels at full droop, as a
/// new Car has them) at least `clearance` m from every static triangle, and one of them
/// within clearance + 0.1 mm of one. Every ellipsoid counts, not a point under the centre,
/// so a wheel over a kerb or a bank that rises under the car lifts the car as a whole.
/// - A car clear of everything at `position` drops straight down onto the first surface
///   it meets (found by rays cast down from each ellipsoid's lowest point).
/// - A car that overlaps something there (a point just above the road, a wheel over a
///   kerb) rises by the least that clears it.
/// The car then rests on what it touches and settles onto its wheels when simulated.
/// Returns the state with zero velocities. Throws trackphys::Error when nothing is below
/// any of the car's ellipsoids, when rising by twice the car's bounding radius does not
/// clear it (a point inside a wall or a hill), for a clearance outside (0, 1] m, for a
/// position or a surface below it more than 1e11 m from y = 0 (doubles there are too coarse
/// for the 0.1 mm it places to), or for an invalid spec or pose (as Car's constructor).
TRACKPHYS_API RigidBodyState place_car_on_surface(const StaticWorld& statics, const CarSpec& car,
                                                  const glm::dvec3& position,
                                                  const glm::dquat& orientation,
                                                  double clearance = 0.001);

}  // namespace trackphys
