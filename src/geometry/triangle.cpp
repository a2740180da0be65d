#include "trackphys/geometry/triangle.hpp"

#include <algorithm>
#include <array>
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

namespace {

double longest_edge_squared(const std::array<glm::dvec3, 3>& v) {
    const auto squared = [](const glm::dvec3& d) { return glm::dot(d, d); };
    return std::max({squared(v[1] - v[0]), squared(v[2] - v[1]), squared(v[0] - v[2])});
}

}  // namespace

double Triangle::longest_edge() const {
    // sqrt is correctly rounded and monotonic, so the root of the largest square is the
    // largest of the three edges' lengths, to the bit.
    return std::sqrt(longest_edge_squared(vertices));
}

bool Triangle::is_degenerate(double relative_tolerance) const {
    // The test below without its roots and division: height > tolerance * longest is
    // |n| > tolerance * longest^2, or |n|^2 > (tolerance * longest^2)^2. Asking for 4 times
    // that leaves room for every rounding of both forms, so a triangle this sure of is not
    // degenerate by the test below either. Edges whose fourth powers could leave the normal
    // range take the test below; the product is squared last so that a tolerance too small
    // to square still compares as the test below would.
    const double longest2 = longest_edge_squared(vertices);
    const glm::dvec3 n = area_normal();
    const double least_normal = relative_tolerance * longest2;
    if (longest2 >= 1e-100 && longest2 <= 1e100 &&
        glm::dot(n, n) > 4.0 * (least_normal * least_normal))
        return false;
    const double longest = std::sqrt(longest2);
    if (!(longest > 0.0)) return true;
    // height over the longest edge = 2 * area / longest
    const double height = glm::length(n) / longest;
    return !(height > relative_tolerance * longest);
}

}  // namespace trackphys
