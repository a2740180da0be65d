#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>

#include <glm/gtc/quaternion.hpp>
#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include "trackphys/export.hpp"
#include "trackphys/geometry/aabb.hpp"
#include "trackphys/math/types.hpp"

namespace trackphys {

namespace detail {
class BodyEllipsoid;
}

/// A rotation that places ellipsoids (Ellipsoid::place_copy): a unit quaternion, its matrix
/// glm::mat3_cast(quaternion) bit for bit, and whether all 13 entries of the two are finite
/// and non-zero. An unrotated ellipsoid's sorted axes are coordinate axes, some negated, and
/// turned by such a rotation glm's products by their ones and zeros come out as the
/// quaternion itself and the matrix's columns, bit for bit (x * 1 + y * 0 + z * 0 is x for
/// a finite non-zero x): placing then copies them rather than multiplying.
struct TRACKPHYS_API PlacingRotation {
    explicit PlacingRotation(const glm::dquat& rotation);
    PlacingRotation(const glm::dquat& rotation, const glm::dmat3& rotation_matrix);

    // Const: placing trusts entries_finite_nonzero to describe the other two.
    const glm::dquat quaternion;
    const glm::dmat3 matrix;
    const bool entries_finite_nonzero;
};

/// A solid ellipsoid: center c, orientation Q (maps local to world) and semi-axes along
/// the local x, y, z axes, in any order.
///
/// The exact kernels want the radii sorted, rx >= ry >= rz
/// (docs/design.md#exact-ellipsoid-triangle-contact), so the ellipsoid also keeps a sorted
/// frame: sorted_radii() and the world directions of the matching axes, sorted_axes()
/// (columns, a proper rotation). to_sorted_local() maps a world point into that frame,
/// where the ellipsoid is x^2/rx^2 + y^2/ry^2 + z^2/rz^2 <= 1.
class TRACKPHYS_API Ellipsoid {
  public:
    /// orientation: any non-zero finite quaternion (it is normalised); semi_axes: all
    /// finite and > 0, in metres. Throws trackphys::Error naming the problem otherwise.
    Ellipsoid(const glm::dvec3& center, const glm::dquat& orientation, const glm::dvec3& semi_axes);

    /// The non-throwing factory: the ellipsoid, or nullopt with the reason in *error.
    static std::optional<Ellipsoid> make(const glm::dvec3& center, const glm::dquat& orientation,
                                         const glm::dvec3& semi_axes, std::string* error = nullptr);

    /// Why these arguments would not make an ellipsoid; empty when they would.
    static std::string validate(const glm::dvec3& center, const glm::dquat& orientation,
                                const glm::dvec3& semi_axes);

    const glm::dvec3& center() const { return center_; }
    /// The unit orientation quaternion (local -> world).
    const glm::dquat& orientation() const { return orientation_; }
    /// The semi-axes as given, along local x, y, z (m).
    const glm::dvec3& semi_axes() const { return semi_axes_; }

    /// The semi-axes sorted descending: x >= y >= z (m).
    const glm::dvec3& sorted_radii() const { return sorted_radii_; }
    /// World directions of the sorted axes as matrix columns (a rotation, det = +1).
    const glm::dmat3& sorted_axes() const { return sorted_axes_; }

    /// A world point in the sorted frame: sorted_axes()^T (p - center()).
    glm::dvec3 to_sorted_local(const glm::dvec3& world_point) const;
    /// A sorted-frame direction in world space: sorted_axes() * v.
    glm::dvec3 sorted_direction_to_world(const glm::dvec3& v) const { return sorted_axes_ * v; }

    /// This ellipsoid carried by the rigid motion x -> rotation * x + translation (a car's
    /// body frame to the world): the radii stay sorted, nothing is validated again, so it
    /// is cheap enough for every ellipsoid of every sub-step. A rotation that is not of unit
    /// length (a lerped quaternion, say) is normalised first; it must be finite and nonzero.
    Ellipsoid transformed(const glm::dquat& rotation, const glm::dvec3& translation) const;
    /// The same written into `copy`, which must already be a copy of this ellipsoid (placed
    /// anywhere), with a unit rotation (unchecked, for the sub-step's sake) and its matrix
    /// given, glm::mat3_cast(rotation), bit for bit: a
    /// car places all its ellipsoids with one matrix, each into its slot, and writes only
    /// what a motion changes (centre, orientation, sorted axes), not the radii.
    void place_copy(Ellipsoid& copy, const glm::dquat& rotation, const glm::dmat3& rotation_matrix,
                    const glm::dvec3& translation) const;
    /// The same with the rotation's matrix and entries checked once for every ellipsoid it
    /// places.
    void place_copy(Ellipsoid& copy, const PlacingRotation& rotation,
                    const glm::dvec3& translation) const;

    /// Radius of the smallest sphere about center() that holds the ellipsoid (m).
    double bounding_radius() const { return sorted_radii_.x; }
    /// The tight axis-aligned world box.
    Aabb bounds() const;

  private:
    friend class detail::BodyEllipsoid;

    struct Unchecked {};
    Ellipsoid(Unchecked, const glm::dvec3& center, const glm::dquat& orientation,
              const glm::dvec3& semi_axes);

    /// For an unrotated ellipsoid (the identity's bits, each sorted axis a coordinate axis,
    /// some negated), which coordinate axis each sorted axis is: what placing copies by.
    struct CoordinateAxes {
        bool unrotated;
        std::array<std::int8_t, 3> along;
    };
    CoordinateAxes coordinate_axes() const;
    /// place_copy with coordinate_axes() given.
    void place_copy(Ellipsoid& copy, const PlacingRotation& rotation, const glm::dvec3& translation,
                    const CoordinateAxes& axes) const;

    glm::dvec3 center_;
    glm::dquat orientation_;
    glm::dvec3 semi_axes_;
    glm::dvec3 sorted_radii_;
    glm::dmat3 sorted_axes_;
};

}  // namespace trackphys
