#pragma once

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

namespace trackphys::geometry_detail {

/// A triangle's own frame from an origin vertex, the end of its first edge and its third
/// vertex: unit dir_x along the first edge, unit normal (CCW) orthogonal to dir_x to
/// rounding, dir_y = normal x dir_x, and the third vertex's local coordinates (x2, y2).
/// Degenerate input gives a finite frame.
struct TriangleFrame {
    glm::dvec3 dir_x, dir_y, normal;
    double x1, x2, y2;
};

inline TriangleFrame make_triangle_frame(const glm::dvec3& origin, const glm::dvec3& edge_end,
                                         const glm::dvec3& third) {
    TriangleFrame f;
    const glm::dvec3 edge = edge_end - origin;
    const glm::dvec3 to_third = third - origin;
    f.x1 = glm::length(edge);
    f.dir_x = f.x1 > 0.0 ? edge / f.x1 : glm::dvec3(1.0, 0.0, 0.0);
    const glm::dvec3 area_normal = glm::cross(edge, to_third);
    const double twice_area = glm::length(area_normal);
    f.normal = twice_area > 0.0 ? area_normal / twice_area : glm::dvec3(0.0, 1.0, 0.0);
    // The cross product's rounding tilts a sliver's normal along its edge by about
    // eps / sin(angle), which lifts the edge's far end off the frame's plane by that times x1:
    // a cull reading the frame would then miss contacts that deep. Removing the normal's part
    // along dir_x puts every vertex on the plane to a few eps of the lengths.
    if (twice_area > 0.0)
        f.normal = glm::normalize(f.normal - glm::dot(f.normal, f.dir_x) * f.dir_x);
    f.dir_y = glm::cross(f.normal, f.dir_x);
    f.x2 = glm::dot(to_third, f.dir_x);
    f.y2 = glm::dot(to_third, f.dir_y);
    return f;
}

}  // namespace trackphys::geometry_detail
