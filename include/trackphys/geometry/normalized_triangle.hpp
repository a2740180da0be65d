#pragma once

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "trackphys/export.hpp"
#include "trackphys/geometry/triangle.hpp"
#include "trackphys/math/types.hpp"

namespace trackphys {

/// A triangle stored in its own frame for the cheapest conservative sphere test
/// (docs/design.md#normalizedtriangle).
///
/// The origin is the start vertex of the longest edge, dir_x runs along that edge and
/// dir_y lies in the plane with dir_x x dir_y = normal. In that frame the vertices are
/// (0, 0), (x1, 0) and (x2, y2) with 0 <= x2 <= x1 and y2 > 0: because the first edge is
/// the longest, the third vertex projects inside it, so the triangle's local bounding box
/// is simply [0, x1] x [0, y2] and the test needs no min/max.
///
/// Stored in double (120 bytes); colliders may keep a more compact copy.
struct TRACKPHYS_API NormalizedTriangle {
    glm::dvec3 origin;  ///< start vertex of the longest edge (m)
    glm::dvec3 dir_x;   ///< unit vector along the longest edge
    glm::dvec3 dir_y;   ///< unit in-plane vector, dir_x x dir_y = normal
    glm::dvec3 normal;  ///< unit normal, same side as the source triangle's CCW normal
    double x1;          ///< longest-edge length (m)
    double x2;          ///< third vertex along dir_x (m), in [0, x1]
    double y2;          ///< third vertex along dir_y (m), > 0

    /// Builds the frame of a non-degenerate triangle (see Triangle::is_degenerate); the
    /// result for a degenerate triangle is finite but meaningless.
    explicit NormalizedTriangle(const Triangle& triangle);

    /// Conservative sphere test, normal first because most candidates are far from the
    /// plane: false only if the sphere (center, radius) cannot touch the triangle. True
    /// means "maybe": the sphere meets the triangle's local box grown by radius. The
    /// write-up's sub-step cull, kept for the benchmarks that measure it against ours
    /// (World culls with ellipsoid_depth_bound alone).
    bool may_touch_sphere(const glm::dvec3& center, double radius) const {
        const glm::dvec3 local = center - origin;
        const double z = glm::dot(normal, local);
        if (z > radius || z < -radius) return false;
        const double x = glm::dot(dir_x, local);
        if (x < -radius || x > x1 + radius) return false;
        const double y = glm::dot(dir_y, local);
        return y >= -radius && y <= y2 + radius;
    }

    /// The world vertices: origin, the longest edge's end, then the third vertex (the
    /// source triangle's vertices rotated, winding kept).
    glm::dvec3 vertex(int i) const;
    Triangle triangle() const { return {vertex(0), vertex(1), vertex(2)}; }
};

}  // namespace trackphys
