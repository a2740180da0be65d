#pragma once

#include <cstddef>
#include <vector>

#include <glm/gtc/quaternion.hpp>
#include <glm/vec3.hpp>

namespace trackphys {

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

}  // namespace trackphys
