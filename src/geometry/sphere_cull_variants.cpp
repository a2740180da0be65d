#include "trackphys/geometry/sphere_cull_variants.hpp"

#include <algorithm>

#include <glm/geometric.hpp>

namespace trackphys {

ArbitraryOriginTriangle::ArbitraryOriginTriangle(const Triangle& triangle) {
    origin = triangle[0];
    const glm::dvec3 edge = triangle[1] - origin;
    const glm::dvec3 to_third = triangle[2] - origin;
    x1 = glm::length(edge);
    dir_x = x1 > 0.0 ? edge / x1 : glm::dvec3(1.0, 0.0, 0.0);
    const glm::dvec3 area_normal = glm::cross(edge, to_third);
    const double twice_area = glm::length(area_normal);
    normal = twice_area > 0.0 ? area_normal / twice_area : glm::dvec3(0.0, 1.0, 0.0);
    dir_y = glm::cross(normal, dir_x);
    x2 = glm::dot(to_third, dir_x);
    y2 = std::max(glm::dot(to_third, dir_y), 0.0);
}

bool ArbitraryOriginTriangle::may_touch_sphere_xyz(const glm::dvec3& center,
                                                   double radius) const {
    const glm::dvec3 local = center - origin;
    const double x = glm::dot(dir_x, local);
    if (x < std::min(0.0, x2) - radius || x > std::max(x1, x2) + radius) return false;
    const double y = glm::dot(dir_y, local);
    if (y < -radius || y > y2 + radius) return false;
    const double z = glm::dot(normal, local);
    return z <= radius && z >= -radius;
}

bool ArbitraryOriginTriangle::may_touch_sphere_normal_first(const glm::dvec3& center,
                                                            double radius) const {
    const glm::dvec3 local = center - origin;
    const double z = glm::dot(normal, local);
    if (z > radius || z < -radius) return false;
    const double x = glm::dot(dir_x, local);
    if (x < std::min(0.0, x2) - radius || x > std::max(x1, x2) + radius) return false;
    const double y = glm::dot(dir_y, local);
    return y >= -radius && y <= y2 + radius;
}

}  // namespace trackphys
