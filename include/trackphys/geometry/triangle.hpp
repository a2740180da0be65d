#pragma once

#include <array>

#include <glm/vec3.hpp>

#include "trackphys/export.hpp"
#include "trackphys/geometry/aabb.hpp"
#include "trackphys/math/types.hpp"

namespace trackphys {

/// A triangle in world space, vertices in counter-clockwise order seen from the side its
/// normal points to (normal = normalize((b - a) x (c - a))).
struct TRACKPHYS_API Triangle {
    std::array<glm::dvec3, 3> vertices;

    Triangle(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) : vertices{a, b, c} {}

    const glm::dvec3& operator[](int i) const { return vertices[static_cast<std::size_t>(i)]; }

    /// (b - a) x (c - a): twice the area times the unit normal.
    glm::dvec3 area_normal() const;
    /// Unit normal; (0,0,0) for a degenerate triangle.
    glm::dvec3 normal() const;
    /// Area (m^2).
    double area() const;
    /// The axis-aligned box of the three vertices.
    Aabb bounds() const;
    /// Length of the longest edge in metres.
    double longest_edge() const;

    /// True when the triangle has (numerically) no area: its height over the longest edge
    /// is below relative_tolerance times that edge, or an edge has zero length. Such
    /// triangles have no reliable normal and are dropped when colliders are built.
    bool is_degenerate(double relative_tolerance = 1e-12) const;
};

}  // namespace trackphys
