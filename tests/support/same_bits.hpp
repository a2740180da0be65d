#pragma once

#include <cstring>

#include <glm/gtc/quaternion.hpp>
#include <glm/vec3.hpp>

#include "trackphys/geometry/contact.hpp"

namespace trackphys::test {

/// Bit-for-bit equality, for results the library promises to reproduce exactly: unlike ==,
/// it tells -0 from +0 and a NaN from a number only by the bits.
inline bool same_bits(const glm::dvec3& a, const glm::dvec3& b) {
    return std::memcmp(&a, &b, sizeof a) == 0;
}

inline bool same_bits(const glm::dquat& a, const glm::dquat& b) {
    return std::memcmp(&a, &b, sizeof a) == 0;
}

inline bool same_bits(const Contact& a, const Contact& b) {
    return std::memcmp(&a.depth, &b.depth, sizeof a.depth) == 0 && same_bits(a.normal, b.normal) &&
           same_bits(a.point, b.point);
}

}  // namespace trackphys::test
