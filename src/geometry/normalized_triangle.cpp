#include "trackphys/geometry/normalized_triangle.hpp"

#include <algorithm>

#include <glm/geometric.hpp>

namespace trackphys {

NormalizedTriangle::NormalizedTriangle(const Triangle& triangle) {
    // Start at the vertex whose outgoing edge (i -> i+1) is the longest, keeping the winding.
    int start = 0;
    double longest_squared = -1.0;
    for (int i = 0; i < 3; ++i) {
        const double length_squared = glm::dot(triangle[(i + 1) % 3] - triangle[i],
                                               triangle[(i + 1) % 3] - triangle[i]);
        if (length_squared > longest_squared) {
            longest_squared = length_squared;
            start = i;
        }
    }
    origin = triangle[start];
    const glm::dvec3 edge = triangle[(start + 1) % 3] - origin;
    const glm::dvec3 to_third = triangle[(start + 2) % 3] - origin;

    x1 = glm::length(edge);
    dir_x = x1 > 0.0 ? edge / x1 : glm::dvec3(1.0, 0.0, 0.0);
    const glm::dvec3 area_normal = glm::cross(edge, to_third);
    const double twice_area = glm::length(area_normal);
    normal = twice_area > 0.0 ? area_normal / twice_area : glm::dvec3(0.0, 1.0, 0.0);
    dir_y = glm::cross(normal, dir_x);

    // Exact arithmetic puts x2 in [0, x1] and y2 > 0; clamp away the last-bit rounding so
    // the cull's box [0, x1] x [0, y2] is the contract the tests check.
    x2 = std::clamp(glm::dot(to_third, dir_x), 0.0, x1);
    y2 = std::max(glm::dot(to_third, dir_y), 0.0);
}

glm::dvec3 NormalizedTriangle::vertex(int i) const {
    switch (i) {
        case 0: return origin;
        case 1: return origin + dir_x * x1;
        default: return origin + dir_x * x2 + dir_y * y2;
    }
}

}  // namespace trackphys
