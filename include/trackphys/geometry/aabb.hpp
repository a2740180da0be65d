#pragma once

#include <limits>

#include <glm/common.hpp>
#include <glm/vec3.hpp>

#include "trackphys/math/types.hpp"

namespace trackphys {

/// Axis-aligned box [min, max] in metres. The default box is empty (min > max), so that
/// growing it by points or boxes starts from nothing.
struct Aabb {
    glm::dvec3 min{std::numeric_limits<double>::infinity()};
    glm::dvec3 max{-std::numeric_limits<double>::infinity()};

    /// True when the box holds no point (some min above its max).
    bool empty() const { return min.x > max.x || min.y > max.y || min.z > max.z; }

    /// Grows the box to hold point p.
    void expand(const glm::dvec3& p) {
        min = glm::min(min, p);
        max = glm::max(max, p);
    }

    /// Grows the box to hold box b (an empty b changes nothing).
    void expand(const Aabb& b) {
        min = glm::min(min, b.min);
        max = glm::max(max, b.max);
    }

    /// The box grown by margin metres on every side.
    Aabb padded(double margin) const { return {min - margin, max + margin}; }

    glm::dvec3 center() const { return 0.5 * (min + max); }
    glm::dvec3 extent() const { return max - min; }

    /// Surface area in m^2 (0 for an empty box); the cost measure of SAH builders.
    double surface_area() const {
        if (empty()) return 0.0;
        const glm::dvec3 e = extent();
        return 2.0 * (e.x * e.y + e.y * e.z + e.z * e.x);
    }

    /// Closed-interval overlap: boxes that only touch do overlap.
    bool overlaps(const Aabb& b) const {
        return min.x <= b.max.x && b.min.x <= max.x && min.y <= b.max.y && b.min.y <= max.y &&
               min.z <= b.max.z && b.min.z <= max.z;
    }

    bool contains(const glm::dvec3& p) const {
        return min.x <= p.x && p.x <= max.x && min.y <= p.y && p.y <= max.y && min.z <= p.z &&
               p.z <= max.z;
    }
    /// True when b lies inside this box (borders included).
    bool contains(const Aabb& b) const { return contains(b.min) && contains(b.max); }
};

}  // namespace trackphys
