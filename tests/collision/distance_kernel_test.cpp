// The distance kernels behind the sphere and capsule queries, against independent
// references: Ericson's closest point in long double, and sampling along the segment.

#include <algorithm>
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "collision/triangle_predicates.hpp"
#include "support/closest_point_reference.hpp"

namespace trackphys {
namespace {

using collision_detail::point_triangle_distance_squared;
using collision_detail::segment_segment_distance_squared;
using collision_detail::segment_triangle_distance_squared;

struct Case {
    glm::dvec3 a, b, c, p, q;
};

// Triangles of mixed sizes (some slivers), points and segments near them.
Case random_case(std::mt19937_64& rng) {
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    const double scale = std::pow(10.0, std::uniform_real_distribution<double>(-1.0, 2.0)(rng));
    const glm::dvec3 offset = glm::dvec3(unit(rng), unit(rng), unit(rng)) * 1000.0;
    auto near = [&] { return offset + glm::dvec3(unit(rng), unit(rng), unit(rng)) * scale; };
    Case k{near(), near(), near(), near() * 1.0, {}};
    if (rng() % 4 == 0) k.c = k.a + (k.b - k.a) * 0.5 + glm::dvec3(0, 1e-6 * scale, 0);
    k.q = rng() % 8 == 0 ? k.p : near();
    return k;
}

double sampled_segment_triangle_distance(const Case& k, int samples) {
    double best = std::numeric_limits<double>::infinity();
    for (int i = 0; i <= samples; ++i) {
        const glm::dvec3 x = k.p + (k.q - k.p) * (double(i) / samples);
        best = std::min(best, double(test::point_triangle_distance(x, k.a, k.b, k.c)));
    }
    return best;
}

TEST(DistanceKernels, PointTriangleMatchesLongDoubleReference) {
    std::mt19937_64 rng(4242);
    for (int i = 0; i < 20000; ++i) {
        const Case k = random_case(rng);
        const double got = std::sqrt(point_triangle_distance_squared(k.p, k.a, k.b, k.c));
        const double want = double(test::point_triangle_distance(k.p, k.a, k.b, k.c));
        ASSERT_NEAR(got, want, 1e-9 + 1e-9 * want) << "case " << i;
    }
}

// Distance to a point is 1-Lipschitz along the segment, so the sampled minimum over N + 1
// evenly spaced points is at most |pq| / (2N) above the true segment distance.
TEST(DistanceKernels, SegmentTriangleMatchesSampledReference) {
    std::mt19937_64 rng(777);
    constexpr int kSamples = 400;
    for (int i = 0; i < 3000; ++i) {
        const Case k = random_case(rng);
        const double got = std::sqrt(segment_triangle_distance_squared(k.p, k.q, k.a, k.b, k.c));
        const double sampled = sampled_segment_triangle_distance(k, kSamples);
        const double slack = glm::length(k.q - k.p) / (2.0 * kSamples);
        ASSERT_LE(got, sampled + 1e-9 * (1 + sampled)) << "case " << i;
        ASSERT_GE(got, sampled - slack - 1e-9 * (1 + sampled)) << "case " << i;
    }
}

TEST(DistanceKernels, SegmentThroughTheTriangleIsAtDistanceZero) {
    const glm::dvec3 a(0, 0, 0), b(4, 0, 0), c(0, 0, -4);
    EXPECT_EQ(segment_triangle_distance_squared({1, 1, -1}, {1, -1, -1}, a, b, c), 0.0);
    EXPECT_EQ(segment_triangle_distance_squared({1, 0, -1}, {1, 0, -1}, a, b, c), 0.0);
    // Parallel above the face: the plane distance.
    EXPECT_DOUBLE_EQ(segment_triangle_distance_squared({0.5, 2, -0.5}, {1.5, 2, -1}, a, b, c), 4.0);
    // Crossing the plane beside the triangle: the distance to the nearest edge (x = 0).
    EXPECT_DOUBLE_EQ(segment_triangle_distance_squared({-1, 1, -1}, {-1, -1, -1}, a, b, c), 1.0);
}

TEST(DistanceKernels, SegmentSegmentSpecialCases) {
    // Crossing, parallel, collinear apart, and point cases.
    EXPECT_EQ(segment_segment_distance_squared({-1, 0, 0}, {1, 0, 0}, {0, -1, 0}, {0, 1, 0}), 0.0);
    EXPECT_DOUBLE_EQ(segment_segment_distance_squared({0, 0, 0}, {1, 0, 0}, {0, 2, 0}, {1, 2, 0}),
                     4.0);
    EXPECT_DOUBLE_EQ(segment_segment_distance_squared({0, 0, 0}, {1, 0, 0}, {3, 0, 0}, {4, 0, 0}),
                     4.0);
    EXPECT_DOUBLE_EQ(segment_segment_distance_squared({0, 0, 0}, {0, 0, 0}, {3, 0, 0}, {4, 0, 0}),
                     9.0);
    EXPECT_DOUBLE_EQ(segment_segment_distance_squared({0, 1, 0}, {0, 1, 0}, {2, 1, 0}, {2, 1, 0}),
                     4.0);
}

}  // namespace
}  // namespace trackphys
