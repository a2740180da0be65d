#pragma once

// Reference closest point on a triangle, in long double: Ericson, "Real-Time Collision
// Detection", 5.1.5 (Voronoi regions of the vertices, edges and face). Tests only.

#include <cmath>

#include <glm/vec3.hpp>

namespace trackphys::test {

struct LVec {
    long double x, y, z;
};
inline LVec lvec(const glm::dvec3& v) { return {v.x, v.y, v.z}; }
inline LVec operator-(LVec a, LVec b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline LVec operator+(LVec a, LVec b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline LVec operator*(LVec a, long double s) { return {a.x * s, a.y * s, a.z * s}; }
inline long double dot(LVec a, LVec b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline long double length(LVec a) { return std::sqrt(dot(a, a)); }

/// Closest point of triangle (a, b, c) to p, all in long double.
inline LVec closest_point_on_triangle(LVec p, LVec a, LVec b, LVec c) {
    const LVec ab = b - a, ac = c - a, ap = p - a;
    const long double d1 = dot(ab, ap), d2 = dot(ac, ap);
    if (d1 <= 0 && d2 <= 0) return a;
    const LVec bp = p - b;
    const long double d3 = dot(ab, bp), d4 = dot(ac, bp);
    if (d3 >= 0 && d4 <= d3) return b;
    const long double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + ab * (d1 / (d1 - d3));
    const LVec cp = p - c;
    const long double d5 = dot(ab, cp), d6 = dot(ac, cp);
    if (d6 >= 0 && d5 <= d6) return c;
    const long double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + ac * (d2 / (d2 - d6));
    const long double va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
        return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
    const long double denom = 1.0L / (va + vb + vc);
    return a + ab * (vb * denom) + ac * (vc * denom);
}

/// Distance from p to the triangle (a, b, c), in long double.
inline long double point_triangle_distance(const glm::dvec3& p, const glm::dvec3& a,
                                           const glm::dvec3& b, const glm::dvec3& c) {
    return length(lvec(p) - closest_point_on_triangle(lvec(p), lvec(a), lvec(b), lvec(c)));
}

}  // namespace trackphys::test
