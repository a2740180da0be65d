#include "trackphys/geometry/sphere_cull_variants.hpp"

#include <algorithm>

#include <glm/geometric.hpp>

#include "geometry/triangle_frame.hpp"

namespace trackphys {

ArbitraryOriginTriangle::ArbitraryOriginTriangle(const Triangle& triangle) {
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
