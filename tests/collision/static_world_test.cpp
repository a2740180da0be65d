#include "trackphys/collision/static_world.hpp"

#include <algorithm>
#include <compare>
#include <cstdint>
#include <limits>
#include <memory>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "collision/collision_meshes.hpp"
#include "support/sanitized.hpp"
#include "trackphys/collision/brute_force_collider.hpp"
#include "trackphys/error.hpp"

namespace trackphys {
namespace {

TEST(SweptBox, CoversStartAndEndPadded) {
    const Aabb box{{0, 0, 0}, {4.5, 1.2, 2}};
    const Aabb swept = swept_box(box, {2.8, 0, -1}, 0.5);
    EXPECT_EQ(swept.min, glm::dvec3(-0.5, -0.5, -1.5));
    EXPECT_EQ(swept.max, glm::dvec3(7.8, 1.7, 2.5));
    EXPECT_THROW(swept_box(box, {0, 0, 0}, -1.0), Error);
}

// The one-word == agrees with comparing the members, and with <=>, whichever member differs
// (including values that differ only in the high half of a word).
TEST(TriangleRef, EqualExactlyWhenBothMembersAre) {
    const std::uint32_t values[] = {0u, 1u, 2u, 0x8000'0000u, 0xffff'ffffu};
    for (std::uint32_t c0 : values)
        for (std::uint32_t t0 : values)
            for (std::uint32_t c1 : values)
                for (std::uint32_t t1 : values) {
                    const TriangleRef a{c0, t0}, b{c1, t1};
                    EXPECT_EQ(a == b, c0 == c1 && t0 == t1);
                    EXPECT_EQ(a != b, !(a == b));
                    EXPECT_EQ(a == b, (a <=> b) == 0);
                }
}

// A world of three colliders (the loop, a soup inside it, the loop again shifted up 0.5 m,
// overlapping): its queries equal the brute-force twins' combined in collider order.
TEST(StaticWorld, MatchesBruteForceOverColliders) {
    std::vector<TriangleMesh> meshes{test::BankedLoop{}.mesh(300), test::random_soup(2000, 3),
                                     test::BankedLoop{}.mesh(300)};
    for (glm::dvec3& v : meshes[2].vertices) v.y += 0.5;
    StaticWorld world;
    std::vector<BruteForceCollider> brute;
    for (const TriangleMesh& mesh : meshes) {
        EXPECT_EQ(world.add(std::make_shared<const StaticCollider>(mesh)), brute.size());
        brute.emplace_back(mesh);
    }
    EXPECT_THROW(world.add(nullptr), Error);
    EXPECT_EQ(world.size(), 3u);
    EXPECT_EQ(world.collider(1).triangle_count(), brute[1].triangle_count());
    EXPECT_THROW(world.collider(3), Error);

    std::mt19937_64 rng(99);
    std::uniform_real_distribution<double> u01(0.0, 1.0), unit(-1.0, 1.0);
    std::vector<TriangleRef> got, want;
    std::vector<std::uint32_t> ids;
    // The first quarter of the same sequence under AddressSanitizer.
    const std::size_t queries = test::kSanitized ? 2500 : 10000;
    std::size_t found = 0, hits = 0;
    for (std::size_t i = 0; i < queries; ++i) {
        const Aabb box =
            i % 5 == 0
                ? Aabb{glm::dvec3(unit(rng), unit(rng), unit(rng)) * 120.0,
                       glm::dvec3(unit(rng), unit(rng), unit(rng)) * 120.0 + glm::dvec3(30.0)}
                : test::BankedLoop{}.car_box(u01(rng), 2.8, 0.5);
        got.clear();
        want.clear();
        world.query_aabb(box, got);
        for (std::uint32_t c = 0; c < brute.size(); ++c) {
            ids.clear();
            brute[c].query_aabb(box, ids);
            for (const std::uint32_t t : ids) want.push_back({c, t});
        }
        std::sort(got.begin(), got.end());
        ASSERT_TRUE(got == want) << "box " << i;
        found += !want.empty();

        // Rays down onto the road (both loops: the shifted one is nearer, except ties).
        const auto frame = test::BankedLoop{}.frame(u01(rng));
        const glm::dvec3 origin = frame.center + frame.left * (unit(rng) * 7.0) +
                                  glm::dvec3(unit(rng), 5.0 + 5.0 * u01(rng), unit(rng));
        const glm::dvec3 dir = glm::normalize(glm::dvec3(unit(rng) * 0.3, -1.0, unit(rng) * 0.3));
        const double max_distance = i % 3 == 0 ? 8.0 : std::numeric_limits<double>::infinity();
        const std::optional<WorldRayHit> hit = world.raycast(origin, dir, max_distance);
        std::optional<WorldRayHit> best;
        for (std::uint32_t c = 0; c < brute.size(); ++c) {
            const std::optional<RayHit> h = brute[c].raycast(origin, dir, max_distance);
            if (h && (!best || h->distance < best->hit.distance)) best = WorldRayHit{c, *h};
        }
        ASSERT_EQ(hit.has_value(), best.has_value()) << "ray " << i;
        if (!best) continue;
        ++hits;
        ASSERT_EQ(hit->collider, best->collider) << "ray " << i;
        ASSERT_EQ(hit->hit.triangle, best->hit.triangle) << "ray " << i;
        ASSERT_EQ(hit->hit.distance, best->hit.distance) << "ray " << i;
    }
    EXPECT_GT(found, queries * 4 / 5);
    EXPECT_GT(hits, queries / 2);
}

}  // namespace
}  // namespace trackphys
