#pragma once

#include <cmath>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

#include "trackphys/dynamics/car_spec.hpp"

namespace trackphys::detail {

/// A wheel's rolling radius: its ellipsoid's half-extent along the body's up axis (y),
/// where it meets a level road, sqrt(y^T R D^2 R^T y) for its orientation R and semi-axes
/// D. The wheel's ellipsoid stays fixed in the body as the wheel spins, so this is its
/// radius whatever way the ellipsoid is turned; for an unturned one it is semi_axes.y, bit
/// for bit (the root of a rounded square is the number squared).
inline double rolling_radius(const CarEllipsoid& wheel) {
    const glm::dvec3 up_in_wheel =
        glm::conjugate(glm::normalize(wheel.orientation)) * glm::dvec3(0.0, 1.0, 0.0);
    const glm::dvec3 scaled = wheel.semi_axes * up_in_wheel;
    return std::sqrt(glm::dot(scaled, scaled));
}

}  // namespace trackphys::detail
