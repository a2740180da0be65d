#pragma once

#include <cstddef>
#include <span>

#include <glm/vec3.hpp>

#include "trackphys/dynamics/car.hpp"

namespace trackphys::detail {

// What World::update and World::restore_state do to a car and a game must not (Car's class
// notes): Car keeps these private and befriends this struct, which only the library and its
// tests include. Each forwards to the Car member of the same name, documented there.
struct CarAccess {
    static void advance(Car& car, std::span<const Contact> deepest, const glm::dvec3& gravity,
                        double h, std::span<const double> grip = {}) {
        car.advance(deepest, gravity, h, grip);
    }
    static void restore(Car& car, const RigidBodyState& state, const CarInputs& inputs,
                        std::span<const double> suspension) {
        car.restore(state, inputs, suspension);
    }
    static void check_restore(const Car& car, const RigidBodyState& state, const CarInputs& inputs,
                              std::span<const double> suspension) {
        car.check_restore(state, inputs, suspension);
    }
    static void push(Car& car, const glm::dvec3& impulse, const glm::dvec3& point) {
        car.push(impulse, point);
    }
    static void set_suspension(Car& car, std::span<const double> travel) {
        car.set_suspension(travel);
    }
    static bool share_ellipsoids_with(Car& car, const Car& other) {
        return car.share_ellipsoids_with(other);
    }
    static void place_ellipsoid(const Car& car, std::size_t i, const PlacingRotation& orientation,
                                Ellipsoid& placed) {
        car.place_ellipsoid(i, orientation, placed);
    }
};

}  // namespace trackphys::detail
