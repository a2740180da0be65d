#pragma once

// The write-up's earlier sphere culls, kept so that the benchmark can reproduce its steps
// (not part of the library's path, which uses NormalizedTriangle):
// 1. origin at the first vertex, tests in x, y, z order (its first version);
// 2. the same layout, normal (z) test first ("about half the cull time");
// 3. NormalizedTriangle: longest-edge origin, so no min/max ("a little more").
// Inline like NormalizedTriangle::may_touch_sphere, so that the three are compiled alike
// and a comparison measures the tests, not a call.

#include <algorithm>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "geometry/triangle_frame.hpp"
#include "trackphys/geometry/triangle.hpp"

namespace trackphys {

/// With the origin at an arbitrary vertex the third vertex may project outside the first
/// edge, so the x range is [min(0, x2), max(x1, x2)] and is computed on every test.
struct ArbitraryOriginTriangle {
    glm::dvec3 origin;  ///< first vertex (m)
    glm::dvec3 dir_x;   ///< unit vector along the first edge
    glm::dvec3 dir_y;   ///< unit in-plane vector, dir_x x dir_y = normal
    glm::dvec3 normal;  ///< unit normal of the CCW triangle
    double x1;          ///< first edge length (m)
    double x2;          ///< third vertex along dir_x (m), any sign
    double y2;          ///< third vertex along dir_y (m), > 0

    explicit ArbitraryOriginTriangle(const Triangle& triangle) {
        origin = triangle[0];
        const geometry_detail::TriangleFrame frame =
            geometry_detail::make_triangle_frame(origin, triangle[1], triangle[2]);
        dir_x = frame.dir_x;
        dir_y = frame.dir_y;
        normal = frame.normal;
        x1 = frame.x1;
        x2 = frame.x2;
        y2 = std::max(frame.y2, 0.0);
    }

    /// Variant 1: x, then y, then the plane distance.
    bool may_touch_sphere_xyz(const glm::dvec3& center, double radius) const {
        const glm::dvec3 local = center - origin;
        const double x = glm::dot(dir_x, local);
        if (x < std::min(0.0, x2) - radius || x > std::max(x1, x2) + radius) return false;
        const double y = glm::dot(dir_y, local);
        if (y < -radius || y > y2 + radius) return false;
        const double z = glm::dot(normal, local);
        return z <= radius && z >= -radius;
    }

    /// Variant 2: the plane distance first, then x and y.
    bool may_touch_sphere_normal_first(const glm::dvec3& center, double radius) const {
        const glm::dvec3 local = center - origin;
        const double z = glm::dot(normal, local);
        if (z > radius || z < -radius) return false;
        const double x = glm::dot(dir_x, local);
        if (x < std::min(0.0, x2) - radius || x > std::max(x1, x2) + radius) return false;
        const double y = glm::dot(dir_y, local);
        return y >= -radius && y <= y2 + radius;
    }
};

}  // namespace trackphys
