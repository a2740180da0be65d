#pragma once

/// trackphys computes in double everywhere (docs/design.md#conventions): positions and
/// velocities keep 1e-5 m anywhere in a 20 km world only in double precision. glm's double
/// types are the public vocabulary: glm::dvec3, glm::dquat (local -> world), glm::dmat3.

#include <cmath>

#include <glm/gtc/quaternion.hpp>
#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

namespace trackphys {

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
