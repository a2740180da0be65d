#include "trackphys/geometry/triangle.hpp"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace trackphys {

glm::dvec3 Triangle::area_normal() const {
    return glm::cross(vertices[1] - vertices[0], vertices[2] - vertices[0]);
}

glm::dvec3 Triangle::normal() const {
    const glm::dvec3 n = area_normal();
    const double length = glm::length(n);
    return length > 0.0 ? n / length : glm::dvec3(0.0);
}

double Triangle::area() const { return 0.5 * glm::length(area_normal()); }

Aabb Triangle::bounds() const {
    Aabb box;
    for (const glm::dvec3& v : vertices) box.expand(v);
    return box;
}

double Triangle::longest_edge() const {
    // One root instead of three, the same double: sqrt is correctly rounded and monotonic,
    // so the root of the largest square is the largest root (glm::distance is that root).
    const auto squared = [](const glm::dvec3& d) { return glm::dot(d, d); };
    return std::sqrt(
        std::max({squared(vertices[1] - vertices[0]), squared(vertices[2] - vertices[1]),
                  squared(vertices[0] - vertices[2])}));
}

bool Triangle::is_degenerate(double relative_tolerance) const {
    const double longest = longest_edge();
    if (!(longest > 0.0)) return true;
    // height over the longest edge = 2 * area / longest
    const double height = glm::length(area_normal()) / longest;
    return !(height > relative_tolerance * longest);
}

}  // namespace trackphys
