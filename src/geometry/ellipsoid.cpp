#include "trackphys/geometry/ellipsoid.hpp"

#include <array>
#include <cmath>
#include <cstring>
#include <string>
#include <utility>

#include <glm/geometric.hpp>

#include "trackphys/assert.hpp"
#include "trackphys/error.hpp"
#include "trackphys/math/types.hpp"

namespace trackphys {

// An empty string, which allocates nothing, for a valid ellipsoid: the constructor runs this
// on every call (a game may build its ellipsoids every frame), so only a refusal formats.
std::string Ellipsoid::validate(const glm::dvec3& center, const glm::dquat& orientation,
                                const glm::dvec3& semi_axes) {
    if (!is_finite(center))
        return "ellipsoid center is not finite (" + exact_text(center.x) + ", " +
               exact_text(center.y) + ", " + exact_text(center.z) + ")";
    if (!is_finite(orientation)) return "ellipsoid orientation quaternion is not finite";
    if (!(glm::length(orientation) > 1e-150)) return "ellipsoid orientation quaternion is zero";
    static constexpr const char* axis_name[3] = {"x", "y", "z"};
    for (int i = 0; i < 3; ++i)
        if (!std::isfinite(semi_axes[i]) || !(semi_axes[i] > 0.0))
            return std::string("ellipsoid semi-axis ") + axis_name[i] +
                   " must be finite and > 0, got " + exact_text(semi_axes[i]);
    return {};
}

Ellipsoid::Ellipsoid(const glm::dvec3& center, const glm::dquat& orientation,
                     const glm::dvec3& semi_axes)
    : Ellipsoid(Unchecked{}, center, orientation, semi_axes) {
    if (std::string why = validate(center, orientation, semi_axes); !why.empty()) throw Error(why);
}

std::optional<Ellipsoid> Ellipsoid::make(const glm::dvec3& center, const glm::dquat& orientation,
                                         const glm::dvec3& semi_axes, std::string* error) {
    std::string why = validate(center, orientation, semi_axes);
    if (!why.empty()) {
        if (error) *error = std::move(why);
        return std::nullopt;
    }
    return Ellipsoid(Unchecked{}, center, orientation, semi_axes);
}

Ellipsoid::Ellipsoid(Unchecked, const glm::dvec3& center, const glm::dquat& orientation,
                     const glm::dvec3& semi_axes)
    : center_(center), semi_axes_(semi_axes) {
    // Validation runs after this constructor in the throwing path; keep every step finite
    // for any input so that a rejected ellipsoid never computes with NaN on the way out.
    const double length = glm::length(orientation);
    orientation_ = length > 1e-150 && std::isfinite(length) ? orientation / length
                                                            : glm::dquat(1.0, 0.0, 0.0, 0.0);
    const glm::dmat3 rotation = glm::mat3_cast(orientation_);

    // Sort the axes by radius, descending; ties keep the given order.
    std::array<int, 3> order = {0, 1, 2};
    for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2 - i; ++j)
            if (semi_axes[order[j]] < semi_axes[order[j + 1]]) std::swap(order[j], order[j + 1]);

    for (int k = 0; k < 3; ++k) {
        sorted_radii_[k] = semi_axes[order[k]];
        sorted_axes_[k] = rotation[order[k]];
    }
    // An odd permutation of the columns flips handedness; flipping one axis (the ellipsoid
    // is symmetric about it) makes the sorted frame a proper rotation again.
    if (glm::dot(glm::cross(sorted_axes_[0], sorted_axes_[1]), sorted_axes_[2]) < 0.0)
        sorted_axes_[2] = -sorted_axes_[2];
}

namespace {

// Which coordinate axis `axis` is (+-1 in that entry, zeros in the others), or -1.
int coordinate_axis_index(const glm::dvec3& axis) {
    if (axis.y == 0.0 && axis.z == 0.0 && std::abs(axis.x) == 1.0) return 0;
    if (axis.x == 0.0 && axis.z == 0.0 && std::abs(axis.y) == 1.0) return 1;
    if (axis.x == 0.0 && axis.y == 0.0 && std::abs(axis.z) == 1.0) return 2;
    return -1;
}

// Whether the 13 entries of a rotation and its matrix are all finite and non-zero. Their
// product is a finite non-zero only if each is (a zero makes it zero or NaN, an infinity
// infinite or NaN, a NaN NaN), which answers for nearly every rotation at once; a zero or
// infinite product may be an underflow or overflow: ask each entry.
bool all_finite_nonzero(const glm::dquat& rotation, const glm::dmat3& matrix) {
    double product = rotation.w * rotation.x * rotation.y * rotation.z;
    for (int k = 0; k < 3; ++k) product *= matrix[k].x * matrix[k].y * matrix[k].z;
    const auto usable = [](double v) { return std::abs(v) > 0.0 && std::isfinite(v); };
    if (usable(product)) return true;
    if (std::isnan(product)) return false;
    bool all = usable(rotation.w) && usable(rotation.x) && usable(rotation.y) && usable(rotation.z);
    for (int k = 0; k < 3; ++k)
        all = all && usable(matrix[k].x) && usable(matrix[k].y) && usable(matrix[k].z);
    return all;
}

}  // namespace

// The matrix built in place: delegating would build it aside and copy it.
PlacingRotation::PlacingRotation(const glm::dquat& rotation)
    : quaternion(rotation),
      matrix(glm::mat3_cast(rotation)),
      entries_finite_nonzero(all_finite_nonzero(quaternion, matrix)) {}

PlacingRotation::PlacingRotation(const glm::dquat& rotation, const glm::dmat3& rotation_matrix)
    : quaternion(rotation),
      matrix(rotation_matrix),
      entries_finite_nonzero(all_finite_nonzero(rotation, rotation_matrix)) {}

Ellipsoid Ellipsoid::transformed(const glm::dquat& rotation, const glm::dvec3& translation) const {
    // A game's interpolated quaternion (a lerp halfway through a 90 degree turn is 0.924
    // long) would scale the axes and move the centre: normalised, as the constructor does.
    // A unit quaternion's rounding (~1e-16) is far inside the tolerance and keeps its bits.
    const double squared = glm::dot(rotation, rotation);
    const glm::dquat unit =
        std::abs(squared - 1.0) > 1e-12 ? rotation / std::sqrt(squared) : rotation;
    Ellipsoid moved = *this;
    place_copy(moved, unit, glm::mat3_cast(unit), translation);
    return moved;
}

void Ellipsoid::place_copy(Ellipsoid& copy, const glm::dquat& rotation,
                           const glm::dmat3& rotation_matrix, const glm::dvec3& translation) const {
    place_copy(copy, PlacingRotation(rotation, rotation_matrix), translation);
}

void Ellipsoid::place_copy(Ellipsoid& copy, const PlacingRotation& rotation,
                           const glm::dvec3& translation) const {
    place_copy(copy, rotation, translation, coordinate_axes());
}

// Unrotated: the identity's bits (one given with a -0 takes the products) and sorted axes
// that are coordinate axes. An ellipsoid turned and turned back can have the first without
// the second, its axes off the coordinate axes by roundings.
Ellipsoid::CoordinateAxes Ellipsoid::coordinate_axes() const {
    static const glm::dquat identity(1.0, 0.0, 0.0, 0.0);
    CoordinateAxes axes{false, {-1, -1, -1}};
    if (std::memcmp(&orientation_, &identity, sizeof identity) != 0) return axes;
    for (int k = 0; k < 3; ++k) {
        axes.along[k] = static_cast<std::int8_t>(coordinate_axis_index(sorted_axes_[k]));
        if (axes.along[k] < 0) return axes;
    }
    axes.unrotated = true;
    return axes;
}

void Ellipsoid::place_copy(Ellipsoid& copy, const PlacingRotation& rotation,
                           const glm::dvec3& translation, const CoordinateAxes& axes) const {
    TP_ASSERT(copy.semi_axes_ == semi_axes_ && copy.sorted_radii_ == sorted_radii_,
              "Ellipsoid::place_copy: the slot is not a copy of this ellipsoid");
    copy.center_ = rotation.matrix * center_ + translation;
    if (axes.unrotated && rotation.entries_finite_nonzero) {
        copy.orientation_ = rotation.quaternion;
        for (int k = 0; k < 3; ++k)
            copy.sorted_axes_[k] = rotation.matrix[axes.along[k]] * sorted_axes_[k][axes.along[k]];
        return;
    }
    copy.orientation_ = rotation.quaternion * orientation_;
    copy.sorted_axes_ = rotation.matrix * sorted_axes_;
}

glm::dvec3 Ellipsoid::to_sorted_local(const glm::dvec3& world_point) const {
    return (world_point - center_) * sorted_axes_;  // row vector times M = M^T * column
}

Aabb Ellipsoid::bounds() const {
    // Half-extent along world axis w is || D * (row w of the rotation) ||.
    glm::dvec3 half_extent;
    for (int w = 0; w < 3; ++w) {
        const glm::dvec3 row(sorted_axes_[0][w] * sorted_radii_.x,
                             sorted_axes_[1][w] * sorted_radii_.y,
                             sorted_axes_[2][w] * sorted_radii_.z);
        half_extent[w] = glm::length(row);
    }
    return {center_ - half_extent, center_ + half_extent};
}

}  // namespace trackphys
