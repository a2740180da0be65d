#pragma once

#include <glm/vec3.hpp>

#include "trackphys/export.hpp"
#include "trackphys/geometry/triangle.hpp"

namespace trackphys {

/// The write-up's earlier sphere culls, kept so the benchmark can reproduce its steps:
/// 1. origin at the first vertex, tests in x, y, z order (its first version);
/// 2. the same layout, normal (z) test first ("about half the cull time");
/// 3. NormalizedTriangle: longest-edge origin, so no min/max ("a little more").
///
/// With the origin at an arbitrary vertex the third vertex may project outside the first
/// edge, so the x range is [min(0, x2), max(x1, x2)] and is computed on every test.
struct TRACKPHYS_API ArbitraryOriginTriangle {
    glm::dvec3 origin;  ///< first vertex (m)
    glm::dvec3 dir_x;   ///< unit vector along the first edge
    glm::dvec3 dir_y;   ///< unit in-plane vector, dir_x x dir_y = normal
    glm::dvec3 normal;  ///< unit normal of the CCW triangle
    double x1;          ///< first edge length (m)
    double x2;          ///< third vertex along dir_x (m), any sign
    double y2;          ///< third vertex along dir_y (m), > 0

    explicit ArbitraryOriginTriangle(const Triangle& triangle);

    /// Variant 1: x, then y, then the plane distance.
    bool may_touch_sphere_xyz(const glm::dvec3& center, double radius) const;
    /// Variant 2: the plane distance first, then x and y.
    bool may_touch_sphere_normal_first(const glm::dvec3& center, double radius) const;
};

}  // namespace trackphys
