// StaticCollider against its BruteForceCollider twin on real tracks (TORCS: a flat road
// course, a banked oval, a road course with bridges, a mountain road): the made-up meshes
// of brute_force_match_test.cpp miss what real tracks have, long steep kerb and wall
// triangles whose boxes hold points metres from their planes. The generic random queries,
// then what a game asks of a track: rays from above the surface straight down (ground
// probes), obliquely down and along the axes (walls), and car-sized boxes on the surface.

#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "collision/brute_force_match.hpp"
#include "support/real_tracks.hpp"
#include "support/sanitized.hpp"
#include "trackphys/collision/brute_force_collider.hpp"
#include "trackphys/collision/static_collider.hpp"

namespace trackphys {
namespace {

// Of each kind below, per track; the first quarter of the same sequence under AddressSanitizer.
constexpr int kTrackQueries = test::kSanitized ? 1000 : 4000;

class RealTrackMatch : public ::testing::TestWithParam<std::string> {};

TEST_P(RealTrackMatch, RandomQueries) {
    TRACKPHYS_REAL_TRACK_OR_SKIP(mesh, GetParam());
    test::expect_same_everywhere(mesh, 77);
}

// A point strictly inside a random kept triangle (barycentric weights >= 1%), with the
// triangle: the surface under a ray cast from above it.
struct SurfacePoint {
    glm::dvec3 point;
    Triangle triangle;
};
SurfacePoint inside_point(const StaticCollider& collider, std::mt19937_64& rng) {
    std::uniform_int_distribution<std::uint32_t> pick(
        0, static_cast<std::uint32_t>(collider.mesh_triangle_count() - 1));
    std::uint32_t index;
    do index = pick(rng);
    while (!collider.has_triangle(index));
    const Triangle t = collider.triangle(index);
    // Uniform on the triangle, then pulled 3% towards its centroid.
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    double u = unit(rng), v = unit(rng);
    if (u + v > 1.0) u = 1.0 - u, v = 1.0 - v;
    u = 0.01 + 0.97 * u;
    v = 0.01 + 0.97 * v;
    return {t[0] + (t[1] - t[0]) * u + (t[2] - t[0]) * v, t};
}

TEST_P(RealTrackMatch, RaysFromAboveTheSurface) {
    TRACKPHYS_REAL_TRACK_OR_SKIP(mesh, GetParam());
    const StaticCollider bvh(mesh);
    const BruteForceCollider brute(mesh);
    std::mt19937_64 rng(88);
    std::uniform_real_distribution<double> log_height(std::log(0.01), std::log(20.0)),
        unit(0.0, 1.0);
    constexpr double kInf = std::numeric_limits<double>::infinity();
    int hits[3] = {0, 0, 0};
    for (int i = 0; i < kTrackQueries; ++i) {
        const SurfacePoint s = inside_point(bvh, rng);
        const double height = std::exp(log_height(rng));
        const glm::dvec3 above = s.point + glm::dvec3(0.0, height, 0.0);
        const double max_distance = unit(rng) < 0.25 ? 200.0 : kInf;

        // Straight down: the triangle the point lies in is below, `height` away; where it
        // is ground (not a wall, whose grazing hit is ill-conditioned), the hit is no
        // farther.
        bool hit = false;
        const test::QueryGenerator::Ray down{above, {0.0, -1.0, 0.0}, max_distance};
        ASSERT_TRUE(test::same_ray_hit(bvh, brute, down, &hit)) << "down ray " << i;
        hits[0] += hit;
        if (std::abs(s.triangle.normal().y) >= 0.5) {
            ASSERT_TRUE(hit) << "down ray " << i << " from " << height << " m above a triangle";
            EXPECT_LE(bvh.raycast(down.origin, down.dir, kInf)->distance, height + 1e-9)
                << "down ray " << i;
        }

        // Obliquely down, 5 to 85 degrees from the vertical, towards any azimuth.
        const double tilt = (5.0 + 80.0 * unit(rng)) * std::numbers::pi / 180.0;
        const double azimuth = 2.0 * std::numbers::pi * unit(rng);
        const glm::dvec3 oblique(std::sin(tilt) * std::cos(azimuth), -std::cos(tilt),
                                 std::sin(tilt) * std::sin(azimuth));
        ASSERT_TRUE(
            test::same_ray_hit(bvh, brute, {above, glm::normalize(oblique), max_distance}, &hit))
            << "oblique ray " << i;
        hits[1] += hit;

        // Along an axis: horizontal (at walls, barriers, slopes) or straight up (bridges).
        glm::dvec3 axis(0.0);
        const int which = static_cast<int>(unit(rng) * 5.0);
        if (which == 4)
            axis.y = 1.0;
        else
            axis[which % 2 == 0 ? 0 : 2] = which < 2 ? 1.0 : -1.0;
        ASSERT_TRUE(test::same_ray_hit(bvh, brute, {above, axis, max_distance}, &hit))
            << "axis ray " << i;
        hits[2] += hit;
    }
    // Down rays hit (checked above); some oblique and axis rays must hit too.
    EXPECT_GT(hits[1], kTrackQueries / 4);
    EXPECT_GT(hits[2], kTrackQueries / 20);
}

TEST_P(RealTrackMatch, CarBoxesOnTheSurface) {
    TRACKPHYS_REAL_TRACK_OR_SKIP(mesh, GetParam());
    const StaticCollider bvh(mesh);
    const BruteForceCollider brute(mesh);
    std::mt19937_64 rng(99);
    std::uniform_real_distribution<double> half(0.3, 3.0), lift(-0.5, 1.5);
    std::vector<std::uint32_t> got, want;
    int found_any = 0;
    for (int i = 0; i < kTrackQueries; ++i) {
        const glm::dvec3 c = inside_point(bvh, rng).point + glm::dvec3(0.0, lift(rng), 0.0);
        const glm::dvec3 h(half(rng), 0.5 * half(rng), half(rng));
        bool found = false;
        ASSERT_TRUE(test::same_box_query(bvh, brute, {c - h, c + h}, got, want, &found))
            << "box " << i;
        found_any += found;
    }
    EXPECT_GT(found_any, kTrackQueries / 2);
}

INSTANTIATE_TEST_SUITE_P(Torcs, RealTrackMatch, ::testing::ValuesIn(test::kRealTracks),
                         test::real_track_test_name);

}  // namespace
}  // namespace trackphys
