#include "trackphys/geometry/normalized_triangle.hpp"

#include <algorithm>
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "geometry/sphere_cull_variants.hpp"
#include "support/closest_point_reference.hpp"

namespace trackphys {
namespace {

glm::dvec3 random_unit(std::mt19937_64& rng) {
    std::normal_distribution<double> normal;
    glm::dvec3 v;
    do v = {normal(rng), normal(rng), normal(rng)};
    while (glm::length(v) < 1e-6);
    return glm::normalize(v);
}

// Random triangles of every shape that matters: ordinary, slivers (one tiny height), needles
// (one tiny edge), huge (kilometres) and far from the origin (a 20 km world).
Triangle random_triangle(std::mt19937_64& rng, int kind) {
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    std::uniform_real_distribution<double> log_scale(-2.0, 3.5);
    const double scale = std::pow(10.0, log_scale(rng));
    const glm::dvec3 offset = kind == 3 ? glm::dvec3(unit(rng), unit(rng), unit(rng)) * 2e4
                                        : glm::dvec3(unit(rng), unit(rng), unit(rng)) * 10.0;
    const glm::dvec3 a = offset + glm::dvec3(unit(rng), unit(rng), unit(rng)) * scale;
    glm::dvec3 b = offset + glm::dvec3(unit(rng), unit(rng), unit(rng)) * scale;
    glm::dvec3 c = offset + glm::dvec3(unit(rng), unit(rng), unit(rng)) * scale;
    if (kind == 1) {  // sliver: c a hair off the line ab
        const double t = std::uniform_real_distribution<double>(-0.2, 1.2)(rng);
        c = a + (b - a) * t + random_unit(rng) * (scale * 1e-6);
    } else if (kind == 2) {  // needle: b a hair from a
        b = a + random_unit(rng) * (scale * 1e-5);
    }
    return {a, b, c};
}

double max_abs(const glm::dvec3& v) {
    return std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
}

TEST(NormalizedTriangle, FrameInvariantsAndReconstruction) {
    std::mt19937_64 rng(12345);
    int checked = 0;
    for (int i = 0; i < 100000; ++i) {
        const Triangle triangle = random_triangle(rng, i % 4);
        if (triangle.is_degenerate()) continue;
        ++checked;
        const NormalizedTriangle n(triangle);
        ASSERT_GE(n.x2, 0.0);
        ASSERT_LE(n.x2, n.x1);
        ASSERT_GT(n.y2, 0.0);
        ASSERT_NEAR(glm::dot(glm::cross(n.dir_x, n.dir_y), n.normal), 1.0, 1e-12);

        // The three vertices come back (as a rotation of the input, winding kept) and the
        // normal matches the input's CCW normal.
        const double scale = std::max({max_abs(triangle[0]), max_abs(triangle[1]),
                                       max_abs(triangle[2]), triangle.longest_edge()});
        int shift = -1;
        for (int s = 0; s < 3; ++s)
            if (glm::length(n.vertex(0) - triangle[s]) == 0.0) shift = s;
        ASSERT_GE(shift, 0) << "origin is not one of the vertices";
        for (int k = 0; k < 3; ++k)
            ASSERT_LE(glm::length(n.vertex(k) - triangle[(shift + k) % 3]), 1e-12 * scale)
                << "vertex " << k << " of triangle " << i;
        // Both normals carry rounding amplified by the triangle's aspect ratio.
        const double condition =
            triangle.longest_edge() * triangle.longest_edge() / glm::length(triangle.area_normal());
        ASSERT_LE(glm::length(n.normal - triangle.normal()), 1e-14 * condition) << "triangle " << i;
    }
    EXPECT_GT(checked, 90000);
}

TEST(NormalizedTriangle, SphereCullNeverRejectsATouchingSphere) {
    std::mt19937_64 rng(777);
    std::uniform_real_distribution<double> unit01(0.0, 1.0);
    int touching = 0, rejected_far = 0;
    for (int i = 0; i < 200000; ++i) {
        const Triangle triangle = random_triangle(rng, i % 4);
        if (triangle.is_degenerate()) continue;
        const NormalizedTriangle normalized(triangle);
        const ArbitraryOriginTriangle arbitrary(triangle);

        // A center near the triangle: a point on it plus an offset of comparable size.
        const double w0 = unit01(rng), w1 = unit01(rng) * (1.0 - w0);
        const glm::dvec3 on =
            triangle[0] + (triangle[1] - triangle[0]) * w0 + (triangle[2] - triangle[0]) * w1;
        const double reach = triangle.longest_edge() * std::pow(10.0, -3.0 * unit01(rng));
        const glm::dvec3 center = on + random_unit(rng) * (reach * 2.0 * unit01(rng));
        const double distance = static_cast<double>(
            test::point_triangle_distance(center, triangle[0], triangle[1], triangle[2]));
        const double radius = reach * unit01(rng);

        // Rounding of the local coordinates: a few ulps of the coordinates' magnitude.
        const double rounding = 1e-13 * std::max(max_abs(center), triangle.longest_edge());
        const bool verdicts[3] = {normalized.may_touch_sphere(center, radius),
                                  arbitrary.may_touch_sphere_xyz(center, radius),
                                  arbitrary.may_touch_sphere_normal_first(center, radius)};
        if (distance <= radius - rounding) {
            ++touching;
            for (int v = 0; v < 3; ++v)
                ASSERT_TRUE(verdicts[v]) << "variant " << v << " rejected a sphere at distance "
                                         << distance << " with radius " << radius;
        } else if (!verdicts[0]) {
            ++rejected_far;
        }
        // Both arbitrary-origin orders test the same box: they always agree.
        ASSERT_EQ(verdicts[1], verdicts[2]);
    }
    EXPECT_GT(touching, 30000);
    EXPECT_GT(rejected_far, 10000) << "the cull should reject most far spheres";
}

TEST(NormalizedTriangle, RejectsSpheresFarFromThePlaneOrBeyondTheEdges) {
    const NormalizedTriangle n(Triangle({0, 0, 0}, {4, 0, 0}, {1, 0, -2}));
    EXPECT_NEAR(n.normal.y, 1.0, 1e-15);
    EXPECT_TRUE(n.may_touch_sphere({1, 0.5, -0.5}, 0.6));
    EXPECT_FALSE(n.may_touch_sphere({1, 0.7, -0.5}, 0.6));     // above the plane
    EXPECT_FALSE(n.may_touch_sphere({1, -0.7, -0.5}, 0.6));    // below the plane
    EXPECT_FALSE(n.may_touch_sphere({-0.7, 0.0, -0.5}, 0.6));  // before the longest edge starts
    EXPECT_FALSE(n.may_touch_sphere({4.7, 0.0, -0.5}, 0.6));   // past its end
    EXPECT_FALSE(n.may_touch_sphere({1, 0.0, 0.7}, 0.6));      // behind the longest edge
    EXPECT_FALSE(n.may_touch_sphere({1, 0.0, -2.7}, 0.6));     // beyond the third vertex
}

}  // namespace
}  // namespace trackphys
