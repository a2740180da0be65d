#pragma once

/// trackphys computes in double everywhere (docs/design.md#conventions): positions and
/// velocities keep 1e-5 m anywhere in a 20 km world only in double precision. glm's double
/// types are the public vocabulary: glm::dvec3, glm::dquat (local -> world), glm::dmat3.

#include <cmath>
#include <cstddef>

#include <glm/gtc/quaternion.hpp>
#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

namespace trackphys {

// The library is compiled with glm's default layout, and its headers hand these types across
// the boundary by reference: a game that includes them with glm settings that change the
// layout would have the library read its vertices and states at the wrong offsets.
static_assert(sizeof(glm::dvec3) == 3 * sizeof(double),
              "trackphys needs glm's default dvec3 of three packed doubles: do not define "
              "GLM_FORCE_DEFAULT_ALIGNED_GENTYPES (or GLM_FORCE_ALIGNED_GENTYPES) where "
              "trackphys headers are included");
static_assert(offsetof(glm::dquat, w) == 3 * sizeof(double),
              "trackphys needs glm's default dquat storage x, y, z, w: do not define "
              "GLM_FORCE_QUAT_DATA_WXYZ where trackphys headers are included");

/// True when every component is finite (neither NaN nor infinite).
inline bool is_finite(const glm::dvec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

/// True when every component is finite.
inline bool is_finite(const glm::dquat& q) {
    return std::isfinite(q.w) && std::isfinite(q.x) && std::isfinite(q.y) && std::isfinite(q.z);
}

/// The absolute value of every component, without branches. glm::abs(dvec3) compiles to
/// x >= 0 ? x : -x with a compare and a branch per component, which mispredicts on random
/// signs (13% of the contact kernel's entry on edge contacts); std::abs clears the sign bit.
inline glm::dvec3 abs_each(const glm::dvec3& v) {
    return {std::abs(v.x), std::abs(v.y), std::abs(v.z)};
}

}  // namespace trackphys
