#include "trackphys/geometry/normalized_triangle.hpp"

#include <algorithm>

#include <glm/geometric.hpp>

#include "geometry/triangle_frame.hpp"

namespace trackphys {

NormalizedTriangle::NormalizedTriangle(const Triangle& triangle) {
    // Start at the vertex whose outgoing edge (i -> i+1) is the longest, keeping the winding.
    int start = 0;
    double longest_squared = -1.0;
    for (int i = 0; i < 3; ++i) {
        const double length_squared =
            glm::dot(triangle[(i + 1) % 3] - triangle[i], triangle[(i + 1) % 3] - triangle[i]);
        if (length_squared > longest_squared) {
            longest_squared = length_squared;
            start = i;
        }
    }
    origin = triangle[start];
    const geometry_detail::TriangleFrame frame = geometry_detail::make_triangle_frame(
        origin, triangle[(start + 1) % 3], triangle[(start + 2) % 3]);
    dir_x = frame.dir_x;
    dir_y = frame.dir_y;
    normal = frame.normal;
    x1 = frame.x1;
    // Exact arithmetic puts x2 in [0, x1] and y2 > 0; clamp away the last-bit rounding so
    // the cull's box [0, x1] x [0, y2] is the contract the tests check.
    x2 = std::clamp(frame.x2, 0.0, x1);
    y2 = std::max(frame.y2, 0.0);
}

glm::dvec3 NormalizedTriangle::vertex(int i) const {
    switch (i) {
        case 0:
            return origin;
        case 1:
            return origin + dir_x * x1;
        default:
            return origin + dir_x * x2 + dir_y * y2;
    }
}

}  // namespace trackphys
