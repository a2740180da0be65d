#pragma once

#include <cstddef>
#include <vector>

#include <glm/gtc/quaternion.hpp>
#include <glm/vec3.hpp>

#include "trackphys/export.hpp"
#include "trackphys/math/types.hpp"

namespace trackphys {

class Car;

/// Where a car is, for drawing it.
struct CarPose {
    glm::dvec3 position{0.0};
    glm::dquat orientation{1.0, 0.0, 0.0, 0.0};
};

/// One wheel of a car as a renderer draws it. The wheel's frame is the body's turned by the
/// steer angle about the body's up axis (+Y), then by the spin angle about the axle (+X,
/// the body's left): a wheel mesh modelled in that frame (axle along X) is drawn at
/// `position` with `orientation`. The wheel ellipsoid's own orientation in the spec
/// (CarEllipsoid::orientation) is not part of it.
struct WheelView {
    std::size_t ellipsoid = 0;  ///< its index in CarSpec::ellipsoids
    /// The wheel ellipsoid's centre in the world (m): Car::world_ellipsoid(i).center(),
    /// which is already where the suspension travel puts it.
    glm::dvec3 position{0.0};
    glm::dquat orientation{1.0, 0.0, 0.0, 0.0};  ///< the wheel's frame (see above)
    double suspension = 0.0;   ///< compression from full droop (m), Car::suspension(i)
    double steer_angle = 0.0;  ///< rad, > 0 to the left: Car::steer_angle() at the front, 0 behind
    /// rad/s about the axle, > 0 rolling forward: the vehicle model's WheelState::spin; 0 for
    /// the arcade car, whose wheels do not spin (their rolling is a force at the contact).
    double spin = 0.0;
    /// rad about the axle: the spin integrated over the published updates (the trapezoid of
    /// each update's two spins), from 0 when the runner was made. A drawing angle, not part
    /// of the simulation; not wrapped (a renderer takes its sine and cosine).
    double spin_angle = 0.0;
};

/// What a renderer and a HUD need of one car after an update: where it is, how it moves,
/// its wheels and its drivetrain. Speed is the length of linear_velocity.
struct CarView {
    CarPose pose;
    glm::dvec3 linear_velocity{0.0};   ///< of the centre of mass, world (m/s)
    glm::dvec3 angular_velocity{0.0};  ///< world (rad/s)
    /// The vehicle model's engine speed of the last sub-step (rev/min; Vehicle::engine_rpm)
    /// and gear (1 = first, -1 = reverse; VehicleState::gear); 0 and 0 for the arcade car,
    /// which has neither.
    double engine_rpm = 0.0;
    int gear = 0;
    std::vector<WheelView> wheels;  ///< the spec's wheels, in CarSpec order
};

/// Brings `view`, the car's view of dt seconds before, to the car's state now, as a
/// PhysicsRunner publishes it after each update (bit for bit): for a game that runs
/// World::update itself. Each wheel's spin angle advances by the trapezoid of its two spins
/// over dt. A view that does not hold this car's wheels (a default CarView, another car's) is
/// made for it first, its spin angles from 0 (dt is then not used); after that, no
/// allocation. Throws trackphys::Error for a dt that is negative or not finite.
TRACKPHYS_API void update_car_view(const Car& car, double dt, CarView& view);

/// The view `alpha` (0..1) of the way from `older` to `newer`, two views of one car, into
/// `out`, as PhysicsRunner::view interpolates (no allocation once out has held as many
/// wheels): older's exactly at 0 and newer's at 1; in between, the position and the other
/// numbers linear, the orientation slerped, each wheel's orientation made from the
/// interpolated body orientation and angles, the gear newer's. Throws trackphys::Error for
/// an alpha outside [0, 1] (NaN too) or views with other wheels.
TRACKPHYS_API void interpolate_car_view(const CarView& older, const CarView& newer, double alpha,
                                        CarView& out);

}  // namespace trackphys
