// Every StaticCollider query against its BruteForceCollider twin: the same triangle sets
// and the same closest hits, on >= 10k random queries per kind and mesh.

#include "collision/brute_force_match.hpp"

#include <vector>

#include <gtest/gtest.h>

#include "collision/collision_meshes.hpp"
#include "trackphys/collision/static_collider.hpp"
#include "trackphys/track/track.hpp"
#include "trackphys/track/track_stats.hpp"

namespace trackphys {
namespace {

using test::expect_same_everywhere;

TEST(BruteForceMatch, RandomSoup) { expect_same_everywhere(test::random_soup(4000, 1), 11); }

TEST(BruteForceMatch, DegenerateHugeAndDuplicateTriangles) {
    std::size_t degenerate = 0;
    const TriangleMesh mesh = test::nasty_mesh(2, &degenerate);
    EXPECT_EQ(StaticCollider(mesh).degenerate_count(), degenerate);
    expect_same_everywhere(mesh, 22);
}

TEST(BruteForceMatch, TrackLikeBankedLoop) {
    expect_same_everywhere(test::BankedLoop{}.mesh(200), 33);
}

// The default generated track (seed 7): the two collider chunks around its tightest banked
// turn, road and walls, as one mesh.
TEST(BruteForceMatch, DefaultTrackTightestTurn) {
    TrackParams params;
    params.seed = 7;
    const Track track = generate_track(params);
    const std::size_t tightest = compute_track_stats(track).tightest_sample;
    std::size_t chunk = 0;
    while (chunk + 1 < track.chunks.size() && track.chunks[chunk + 1].first_sample <= tightest)
        ++chunk;
    TriangleMesh mesh;
    for (std::size_t c : {chunk, (chunk + 1) % track.chunks.size()}) {
        const TriangleMesh& part = track.chunks[c].mesh;
        const auto base = static_cast<std::uint32_t>(mesh.vertices.size());
        mesh.vertices.insert(mesh.vertices.end(), part.vertices.begin(), part.vertices.end());
        for (const auto& t : part.triangles)
            mesh.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
    }
    expect_same_everywhere(mesh, 55);
}

}  // namespace
}  // namespace trackphys

namespace trackphys {
namespace {

// Far from the origin (a 30 km world) float node bounds are ~2 mm coarse, bigger than the
// smallest triangles here: the outward rounding must keep every answer exact.
TEST(BruteForceMatch, FarFromTheOrigin) {
    TriangleMesh mesh = test::random_soup(3000, 4);
    for (glm::dvec3& v : mesh.vertices) v = glm::dvec3(15000.0, 300.0, -12000.0) + v * 0.05;
    expect_same_everywhere(mesh, 44);
}

// Flat ground: every leaf box has zero extent in y (its 16-bit grid falls back to the
// float spacing there, no division by the extent), and touching query boxes meet it
// exactly at y = height; at 0 and at a height where float spacing is 1/16 m.
TEST(BruteForceMatch, FlatGround) {
    for (const double height : {0.0, 1.0e6}) {
        TriangleMesh mesh;
        constexpr std::uint32_t kCells = 50;
        for (std::uint32_t i = 0; i <= kCells; ++i)
            for (std::uint32_t j = 0; j <= kCells; ++j)
                mesh.vertices.push_back({0.37 * i - 4.0, height, 0.29 * j + 1.0});
        for (std::uint32_t i = 0; i < kCells; ++i)
            for (std::uint32_t j = 0; j < kCells; ++j) {
                const std::uint32_t v = i * (kCells + 1) + j;
                mesh.triangles.push_back({v, v + 1, v + kCells + 1});
                mesh.triangles.push_back({v + 1, v + kCells + 2, v + kCells + 1});
            }
        expect_same_everywhere(mesh, 66);
    }
}

}  // namespace
}  // namespace trackphys
