#pragma once

#include <cstddef>
#include <span>

#include "trackphys/vehicle/vehicle.hpp"

namespace trackphys::detail {

// The sub-step of a vehicle model, which Car's sub-step drives and a game must not (Vehicle's
// class notes): Vehicle keeps these private and befriends this struct, which only the library
// and its tests include. Each forwards to the Vehicle member of the same name, documented there.
struct VehicleAccess {
    static void begin_substep(Vehicle& vehicle, double throttle, double brake, double car_speed,
                              double forward_speed, double h) {
        vehicle.begin_substep(throttle, brake, car_speed, forward_speed, h);
    }
    static TyreForce wheel_force(Vehicle& vehicle, std::size_t w, double load,
                                 double rolling_velocity, double lateral_velocity, double h,
                                 double surface_grip = 1.0) {
        return vehicle.wheel_force(w, load, rolling_velocity, lateral_velocity, h, surface_grip);
    }
    static void measure_anti_roll(Vehicle& vehicle, std::span<const double> suspension) {
        vehicle.measure_anti_roll(suspension);
    }
    static double engine_torque(const Vehicle& vehicle, double rpm, double throttle) {
        return vehicle.engine_torque(rpm, throttle);
    }
};

}  // namespace trackphys::detail
