#pragma once

#include <glm/vec3.hpp>

#include "trackphys/geometry/ellipsoid.hpp"
#include "trackphys/math/types.hpp"

namespace trackphys {

namespace detail {

/// Internal (the car's shape holds these): an ellipsoid in a moving body's frame, placed in
/// the world again and again (a car's, at every sub-step), with what Ellipsoid::place_copy
/// would otherwise find at each placing, whether it is unrotated and which coordinate axis
/// each sorted axis is, found once. Its ellipsoid changes only by building a new one, which
/// finds them again: they cannot go stale.
class BodyEllipsoid {
  public:
    explicit BodyEllipsoid(const Ellipsoid& ellipsoid)
        : ellipsoid_(ellipsoid), axes_(ellipsoid.coordinate_axes()) {}

    const Ellipsoid& ellipsoid() const { return ellipsoid_; }

    /// ellipsoid().place_copy(copy, rotation, translation), the same bits.
    void place_copy(Ellipsoid& copy, const PlacingRotation& rotation,
                    const glm::dvec3& translation) const {
        ellipsoid_.place_copy(copy, rotation, translation, axes_);
    }

  private:
    Ellipsoid ellipsoid_;
    Ellipsoid::CoordinateAxes axes_;
};

}  // namespace detail
}  // namespace trackphys
