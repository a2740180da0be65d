#pragma once

// The brute-force match harness: random queries of every kind on one mesh, each answered by
// StaticCollider and by its BruteForceCollider twin, which must agree exactly (the same
// triangle sets, the same closest hits). Used by brute_force_match_test.cpp (made-up meshes)
// and real_track_match_test.cpp (TORCS tracks).

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <optional>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "support/sanitized.hpp"
#include "trackphys/collision/brute_force_collider.hpp"
#include "trackphys/collision/static_collider.hpp"
#include "trackphys/geometry/aabb.hpp"
#include "trackphys/geometry/triangle.hpp"
#include "trackphys/geometry/triangle_mesh.hpp"

namespace trackphys::test {

// Of each kind, per mesh; the first quarter of the same sequence under AddressSanitizer.
constexpr int kQueries = kSanitized ? 2500 : 10000;

// Random query material for one mesh: points near its vertices, edges and faces (where
// the predicates' boundaries are), uniform in its padded bounds, and far away.
class QueryGenerator {
  public:
    QueryGenerator(const TriangleMesh& mesh, std::uint64_t seed) : mesh_(mesh), rng_(seed) {
        for (const glm::dvec3& v : mesh.vertices) bounds_.expand(v);
        scale_ = glm::length(bounds_.extent());
    }

    double uniform(double lo, double hi) {
        return std::uniform_real_distribution<double>(lo, hi)(rng_);
    }
    double log_uniform(double lo, double hi) {
        return std::exp(uniform(std::log(lo), std::log(hi)));
    }
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
        const auto& tri =
            mesh_.triangles[static_cast<std::size_t>(pick(int(mesh_.triangles.size())))];
        const glm::dvec3 a = mesh_.vertices[tri[0]], b = mesh_.vertices[tri[1]],
                         c = mesh_.vertices[tri[2]];
        switch (pick(3)) {
            case 0:
                return a;
            case 1:
                return a + (b - a) * uniform(0.0, 1.0);
            default: {
                double u = uniform(0.0, 1.0), v = uniform(0.0, 1.0);
                if (u + v > 1.0) u = 1.0 - u, v = 1.0 - v;
                return a + (b - a) * u + (c - a) * v;
            }
        }
    }

    glm::dvec3 point() {
        switch (pick(10)) {
            case 0:
                return bounds_.center() + unit_vector() * (scale_ * 1e4);
            case 1:
            case 2: {
                const Aabb b = bounds_.padded(0.1 * scale_);
                return {uniform(b.min.x, b.max.x), uniform(b.min.y, b.max.y),
                        uniform(b.min.z, b.max.z)};
            }
            case 3:
                return surface_point();  // exactly on the surface
            default:
                return surface_point() + unit_vector() * log_uniform(1e-6, 0.05) * scale_;
        }
    }

    double radius() { return pick(20) == 0 ? 0.0 : log_uniform(1e-4, 0.2) * scale_; }

    Aabb box() {
        const glm::dvec3 c = point();
        if (pick(5) == 0) {  // corner exactly on a vertex: touching boxes
            const glm::dvec3 v =
                mesh_.vertices[static_cast<std::size_t>(pick(int(mesh_.vertices.size())))];
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

inline std::vector<std::uint32_t> sorted(std::vector<std::uint32_t> v) {
    std::sort(v.begin(), v.end());
    return v;
}

/// The BVH and the brute force report the same triangles for the box (`got` and `want` are
/// scratch); *found says whether there were any.
inline ::testing::AssertionResult same_box_query(const StaticCollider& bvh,
                                                 const BruteForceCollider& brute, const Aabb& box,
                                                 std::vector<std::uint32_t>& got,
                                                 std::vector<std::uint32_t>& want, bool* found) {
    got.clear();
    want.clear();
    bvh.query_aabb(box, got);
    brute.query_aabb(box, want);
    *found = !want.empty();
    if (sorted(got) == want) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure()
           << "box (" << box.min.x << ", " << box.min.y << ", " << box.min.z << ")-(" << box.max.x
           << ", " << box.max.y << ", " << box.max.z << "): " << got.size()
           << " triangles, brute force " << want.size();
}

/// The BVH and the brute force agree on the ray's closest hit (whether there is one, its
/// triangle, its distance to 1e-12 relative, its normal), within max_distance; *hit says
/// whether there was one. Both share one predicate, so the hit is also checked without it:
/// its point must lie on its triangle's plane (to 1e-9 of the lengths involved, times the
/// triangle's conditioning: far above rounding), which a hit at a wrong distance does not.
inline ::testing::AssertionResult same_ray_hit(const StaticCollider& bvh,
                                               const BruteForceCollider& brute,
                                               const QueryGenerator::Ray& ray, bool* hit) {
    const std::optional<RayHit> g = bvh.raycast(ray.origin, ray.dir, ray.max_distance);
    const std::optional<RayHit> w = brute.raycast(ray.origin, ray.dir, ray.max_distance);
    *hit = w.has_value();
    auto failure = [&] {
        return ::testing::AssertionFailure()
               << std::setprecision(17) << "origin (" << ray.origin.x << ", " << ray.origin.y
               << ", " << ray.origin.z << ") dir (" << ray.dir.x << ", " << ray.dir.y << ", "
               << ray.dir.z << ") max " << ray.max_distance << ": ";
    };
    if (g.has_value() != w.has_value())
        return failure() << "hit " << g.has_value() << ", brute force " << w.has_value();
    if (!w) return ::testing::AssertionSuccess();
    const double tolerance = 1e-12 * std::max(1.0, w->distance);
    if (g->triangle != w->triangle || !(std::abs(g->distance - w->distance) <= tolerance) ||
        g->normal != w->normal)
        return failure() << "triangle " << g->triangle << " at " << g->distance << ", brute force "
                         << w->triangle << " at " << w->distance;
    if (!(w->distance >= 0.0 && w->distance <= ray.max_distance))
        return failure() << "distance " << w->distance << " outside [0, max]";
    const Triangle t = bvh.triangle(w->triangle);
    const glm::dvec3 e1 = t[1] - t[0], e2 = t[2] - t[0];
    const glm::dvec3 point = ray.origin + ray.dir * w->distance;
    const double off_plane = std::abs(glm::dot(point - t[0], w->normal));
    // The normal of a sliver is only as good as 1 / sin of its angle.
    const double conditioning = glm::length(e1) * glm::length(e2) / glm::length(glm::cross(e1, e2));
    const double scale =
        1.0 + glm::length(ray.origin - t[0]) + w->distance + glm::length(e1) + glm::length(e2);
    if (!(off_plane <= 1e-9 * scale * conditioning))
        return failure() << "hit on triangle " << w->triangle << " at " << w->distance << " is "
                         << off_plane << " m off its plane";
    return ::testing::AssertionSuccess();
}

inline void expect_same_everywhere(const TriangleMesh& mesh, std::uint64_t seed) {
    const StaticCollider bvh(mesh);
    const BruteForceCollider brute(mesh);
    ASSERT_EQ(bvh.triangle_count(), brute.triangle_count());
    QueryGenerator gen(mesh, seed);
    std::vector<std::uint32_t> got, want;
    std::size_t nonempty[3] = {0, 0, 0}, ray_hits = 0;

    for (int i = 0; i < kQueries; ++i) {
        bool found = false;
        ASSERT_TRUE(same_box_query(bvh, brute, gen.box(), got, want, &found)) << "aabb query " << i;
        nonempty[0] += found;
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
        bool hit = false;
        ASSERT_TRUE(same_ray_hit(bvh, brute, gen.ray(), &hit)) << "ray " << i;
        ray_hits += hit;
    }
    // The queries must exercise the predicates, not just miss everything.
    EXPECT_GT(nonempty[0], kQueries / 3);
    EXPECT_GT(nonempty[1], kQueries / 5);
    EXPECT_GT(nonempty[2], kQueries / 5);
    EXPECT_GT(ray_hits, std::size_t{kQueries} / 3);
}

}  // namespace trackphys::test
