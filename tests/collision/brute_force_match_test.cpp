// Every StaticCollider query against its BruteForceCollider twin: the same triangle sets
// and the same closest hits, on >= 10k random queries per kind and mesh.

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "collision/collision_meshes.hpp"
#include "trackphys/collision/brute_force_collider.hpp"
#include "trackphys/collision/static_collider.hpp"
#include "trackphys/track/track.hpp"
#include "trackphys/track/track_stats.hpp"

namespace trackphys {
namespace {

constexpr int kQueries = 10000;

// Random query material for one mesh: points near its vertices, edges and faces (where
// the predicates' boundaries are), uniform in its padded bounds, and far away.
class QueryGenerator {
public:
    QueryGenerator(const TriangleMesh& mesh, std::uint64_t seed) : mesh_(mesh), rng_(seed) {
        for (const glm::dvec3& v : mesh.vertices) bounds_.expand(v);
        scale_ = glm::length(bounds_.extent());
    }

    double uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng_); }
    double log_uniform(double lo, double hi) { return std::exp(uniform(std::log(lo), std::log(hi))); }
    int pick(int n) { return std::uniform_int_distribution<int>(0, n - 1)(rng_); }

    glm::dvec3 unit_vector() {
        std::normal_distribution<double> normal;
        glm::dvec3 v;
        do v = {normal(rng_), normal(rng_), normal(rng_)};
        while (glm::length(v) < 1e-3);
        v = glm::normalize(v);
        if (pick(10) == 0) v[pick(3)] = 0.0;  // zero components: rays in slab planes
        if (pick(10) == 0) v = glm::dvec3(0.0);
        if (v == glm::dvec3(0.0)) v[pick(3)] = pick(2) ? 1.0 : -1.0;
        return glm::normalize(v);
    }

    // A point on a random triangle: a vertex, an edge point or an interior point.
    glm::dvec3 surface_point() {
        const auto& tri = mesh_.triangles[static_cast<std::size_t>(pick(int(mesh_.triangles.size())))];
        const glm::dvec3 a = mesh_.vertices[tri[0]], b = mesh_.vertices[tri[1]],
                         c = mesh_.vertices[tri[2]];
        switch (pick(3)) {
            case 0: return a;
            case 1: return a + (b - a) * uniform(0.0, 1.0);
            default: {
                double u = uniform(0.0, 1.0), v = uniform(0.0, 1.0);
                if (u + v > 1.0) u = 1.0 - u, v = 1.0 - v;
                return a + (b - a) * u + (c - a) * v;
            }
        }
    }

    glm::dvec3 point() {
        switch (pick(10)) {
            case 0: return bounds_.center() + unit_vector() * (scale_ * 1e4);
            case 1:
            case 2: {
                const Aabb b = bounds_.padded(0.1 * scale_);
                return {uniform(b.min.x, b.max.x), uniform(b.min.y, b.max.y),
                        uniform(b.min.z, b.max.z)};
            }
            case 3: return surface_point();  // exactly on the surface
            default: return surface_point() + unit_vector() * log_uniform(1e-6, 0.05) * scale_;
        }
    }

    double radius() { return pick(20) == 0 ? 0.0 : log_uniform(1e-4, 0.2) * scale_; }

    Aabb box() {
        const glm::dvec3 c = point();
        if (pick(5) == 0) {  // corner exactly on a vertex: touching boxes
            const glm::dvec3 v = mesh_.vertices[static_cast<std::size_t>(pick(int(mesh_.vertices.size())))];
            const glm::dvec3 size(log_uniform(1e-3, 0.3) * scale_);
            return pick(2) ? Aabb{v, v + size} : Aabb{v - size, v};
        }
        const glm::dvec3 half(log_uniform(1e-4, 0.3) * scale_, log_uniform(1e-4, 0.3) * scale_,
                              log_uniform(1e-4, 0.3) * scale_);
        return {c - half, c + half};
    }

    struct Ray {
        glm::dvec3 origin, dir;
        double max_distance;
    };
    Ray ray() {
        Ray r;
        r.origin = point();
        if (pick(6) == 0) {  // axis-parallel at a surface point (a ground probe): zero components
            glm::dvec3 axis(0.0);
            axis[pick(3)] = pick(2) ? 1.0 : -1.0;
            r.dir = axis;
            r.origin = surface_point() - axis * (log_uniform(1e-3, 1.0) * scale_);
        } else if (pick(4) == 0) {
            r.dir = unit_vector();
        } else {  // aimed at a vertex, edge or face point: hits, shared edges, ties
            glm::dvec3 to = surface_point() - r.origin;
            if (glm::length(to) == 0.0) to = unit_vector();
            r.dir = glm::normalize(to);
        }
        r.max_distance = pick(3) == 0 ? log_uniform(1e-3, 2.0) * scale_
                                      : std::numeric_limits<double>::infinity();
        return r;
    }

private:
    const TriangleMesh& mesh_;
    std::mt19937_64 rng_;
    Aabb bounds_;
    double scale_ = 1.0;
};

std::vector<std::uint32_t> sorted(std::vector<std::uint32_t> v) {
    std::sort(v.begin(), v.end());
    return v;
}

void expect_same_everywhere(const TriangleMesh& mesh, std::uint64_t seed) {
    const StaticCollider bvh(mesh);
    const BruteForceCollider brute(mesh);
    ASSERT_EQ(bvh.triangle_count(), brute.triangle_count());
    QueryGenerator gen(mesh, seed);
    std::vector<std::uint32_t> got, want;
    std::size_t nonempty[3] = {0, 0, 0}, ray_hits = 0;

    for (int i = 0; i < kQueries; ++i) {
        const Aabb box = gen.box();
        got.clear();
        want.clear();
        bvh.query_aabb(box, got);
        brute.query_aabb(box, want);
        ASSERT_EQ(sorted(got), want) << "aabb query " << i;
        nonempty[0] += !want.empty();
    }
    for (int i = 0; i < kQueries; ++i) {
        const glm::dvec3 c = gen.point();
        const double r = gen.radius();
        got.clear();
        want.clear();
        bvh.query_sphere(c, r, got);
        brute.query_sphere(c, r, want);
        ASSERT_EQ(sorted(got), want) << "sphere query " << i;
        nonempty[1] += !want.empty();
    }
    for (int i = 0; i < kQueries; ++i) {
        const glm::dvec3 a = gen.point();
        const glm::dvec3 b = gen.pick(10) == 0 ? a : a + gen.unit_vector() * gen.radius() * 3.0;
        const double r = gen.radius();
        got.clear();
        want.clear();
        bvh.query_capsule(a, b, r, got);
        brute.query_capsule(a, b, r, want);
        ASSERT_EQ(sorted(got), want) << "capsule query " << i;
        nonempty[2] += !want.empty();
    }
    for (int i = 0; i < kQueries; ++i) {
        const auto ray = gen.ray();
        const std::optional<RayHit> g = bvh.raycast(ray.origin, ray.dir, ray.max_distance);
        const std::optional<RayHit> w = brute.raycast(ray.origin, ray.dir, ray.max_distance);
        ASSERT_EQ(g.has_value(), w.has_value()) << "ray " << i;
        if (!w) continue;
        ++ray_hits;
        ASSERT_EQ(g->triangle, w->triangle) << "ray " << i;
        ASSERT_LE(std::abs(g->distance - w->distance), 1e-12 * std::max(1.0, w->distance));
        ASSERT_EQ(g->normal, w->normal);
        ASSERT_LE(w->distance, ray.max_distance);
    }
    // The queries must exercise the predicates, not just miss everything.
    EXPECT_GT(nonempty[0], kQueries / 3);
    EXPECT_GT(nonempty[1], kQueries / 5);
    EXPECT_GT(nonempty[2], kQueries / 5);
    EXPECT_GT(ray_hits, std::size_t{kQueries} / 3);
}

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
    while (chunk + 1 < track.chunks.size() && track.chunks[chunk + 1].first_sample <= tightest) ++chunk;
    TriangleMesh mesh;
    for (std::size_t c : {chunk, (chunk + 1) % track.chunks.size()}) {
        const TriangleMesh& part = track.chunks[c].mesh;
        const auto base = static_cast<std::uint32_t>(mesh.vertices.size());
        mesh.vertices.insert(mesh.vertices.end(), part.vertices.begin(), part.vertices.end());
        for (const auto& t : part.triangles) mesh.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
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
