// The world's top-level tree over colliders: every query equals the loop over all colliders
// in id order, whatever the order the colliders come in, with empty colliders, boxes that
// hit more colliders than a query prefetches at once, boxes between a collider's exact and
// float boxes, and after adding more colliders once the tree was built.
#include <algorithm>
#include <memory>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "trackphys/collision/static_world.hpp"

namespace trackphys {
namespace {

// A 4 x 4 m tile of two triangles with its corner at (x, y, z), tilted a little.
TriangleMesh tile(double x, double y, double z) {
    TriangleMesh m;
    m.vertices = {{x, y, z}, {x + 4, y + 0.3, z}, {x + 4, y, z + 4}, {x, y - 0.2, z + 4}};
    m.triangles = {{0, 2, 1}, {0, 3, 2}};
    return m;
}

// Tiles on a 60 x 60 grid 5 m apart, in row order or shuffled, every 97th empty.
std::shared_ptr<StaticWorld> tiles(bool shuffled) {
    std::vector<TriangleMesh> meshes;
    std::mt19937 rng(4);
    std::uniform_real_distribution<double> height(-1.0, 1.0);
    for (int i = 0; i < 60; ++i)
        for (int j = 0; j < 60; ++j)
            meshes.push_back(meshes.size() % 97 == 5 ? TriangleMesh{}
                                                     : tile(i * 5.0, height(rng), j * 5.0));
    if (shuffled) std::shuffle(meshes.begin(), meshes.end(), rng);
    auto world = std::make_shared<StaticWorld>();
    for (const TriangleMesh& m : meshes) world->add(std::make_shared<StaticCollider>(m));
    return world;
}

// The loop over every collider in id order: what StaticWorld did before it had a tree.
std::vector<TriangleRef> brute_aabb(const StaticWorld& w, const Aabb& box) {
    std::vector<TriangleRef> out;
    for (std::uint32_t id = 0; id < w.size(); ++id)
        if (w.collider(id).bounds().overlaps(box)) w.collider(id).query_aabb_refs(box, id, out);
    return out;
}
std::vector<std::uint32_t> brute_ids(const StaticWorld& w, const Aabb& box) {
    std::vector<std::uint32_t> out;
    for (std::uint32_t id = 0; id < w.size(); ++id)
        if (w.collider(id).bounds().overlaps(box)) out.push_back(id);
    return out;
}
std::optional<WorldRayHit> brute_ray(const StaticWorld& w, const glm::dvec3& o, const glm::dvec3& d,
                                     double max) {
    std::optional<WorldRayHit> best;
    for (std::uint32_t id = 0; id < w.size(); ++id) {
        const auto hit = w.collider(id).raycast(o, d, best ? best->hit.distance : max);
        if (hit && (!best || hit->distance < best->hit.distance)) best = WorldRayHit{id, *hit};
    }
    return best;
}

void expect_brute_force(const StaticWorld& w, int queries) {
    std::mt19937 rng(9);
    std::uniform_real_distribution<double> u(-20.0, 320.0), size(0.0, 30.0), unit(-1.0, 1.0);
    std::vector<TriangleRef> refs;
    std::vector<std::uint32_t> ids;
    for (int q = 0; q < queries; ++q) {
        const glm::dvec3 c(u(rng), unit(rng), u(rng));
        const Aabb box = Aabb{c, c}.padded(q % 50 == 0 ? 200.0 : size(rng));
        refs.clear();
        w.query_aabb(box, refs);
        ASSERT_EQ(refs, brute_aabb(w, box)) << q;
        ids.clear();
        w.colliders_overlapping(box, ids);
        ASSERT_EQ(ids, brute_ids(w, box)) << q;
        const glm::dvec3 d = glm::normalize(glm::dvec3(unit(rng), unit(rng) - 1.5, unit(rng)));
        const glm::dvec3 o = c + glm::dvec3(0.0, 20.0, 0.0);
        const auto hit = w.raycast(o, d, 400.0), expected = brute_ray(w, o, d, 400.0);
        ASSERT_EQ(hit.has_value(), expected.has_value()) << q;
        if (hit) {
            EXPECT_EQ(hit->collider, expected->collider) << q;
            EXPECT_EQ(hit->hit.triangle, expected->hit.triangle) << q;
            EXPECT_EQ(hit->hit.distance, expected->hit.distance) << q;
        }
    }
}

TEST(ColliderTree, QueriesEqualTheLoopOverAllColliders) { expect_brute_force(*tiles(false), 1000); }

TEST(ColliderTree, AnyColliderOrderGivesTheSameAnswersAsTheLoop) {
    expect_brute_force(*tiles(true), 1000);
}

TEST(ColliderTree, CollidersAddedAfterAQueryAreFound) {
    auto world = tiles(false);
    std::vector<TriangleRef> refs;
    const Aabb far{{1000, -5, 1000}, {1010, 5, 1010}};
    world->query_aabb(far, refs);
    EXPECT_TRUE(refs.empty());
    const std::uint32_t id = world->add(std::make_shared<StaticCollider>(tile(1002, 0, 1002)));
    world->query_aabb(far, refs);
    ASSERT_EQ(refs.size(), 2u);
    EXPECT_EQ(refs[0].collider, id);
    expect_brute_force(*world, 200);
}

// The tree tests lane boxes rounded outward to float: a box that only touches a collider's
// float box is no overlap with its exact one.
TEST(ColliderTree, ABoxBetweenAColliderAndItsFloatBoxFindsNothing) {
    const double x = 1.0 + 0x1p-30;  // the float below it is 1, the collider's float min
    TriangleMesh m;
    m.vertices = {{x, 0, 0}, {x + 1, 0, 0}, {x, 0, 1}};
    m.triangles = {{0, 2, 1}};
    StaticWorld world;
    for (int i = 0; i < 20; ++i) world.add(std::make_shared<StaticCollider>(tile(10.0 * i, 0, 5)));
    const std::uint32_t id = world.add(std::make_shared<StaticCollider>(m));
    const Aabb touching_float{{0.5, -1, -1}, {1.0 + 0x1p-31, 1, 2}};
    const Aabb touching_exact{{0.5, -1, -1}, {x, 1, 2}};
    std::vector<std::uint32_t> ids;
    world.colliders_overlapping(touching_float, ids);
    EXPECT_TRUE(ids.empty());
    std::vector<TriangleRef> refs;
    world.query_aabb(touching_float, refs);
    EXPECT_TRUE(refs.empty());
    world.colliders_overlapping(touching_exact, ids);
    EXPECT_EQ(ids, std::vector<std::uint32_t>{id});
    world.query_aabb(touching_exact, refs);
    EXPECT_EQ(refs, (std::vector<TriangleRef>{{id, 0}}));
}

TEST(ColliderTree, AMovedWorldKeepsItsTreeAndTheMovedFromOneWorksAgain) {
    StaticWorld world;
    world.add(std::make_shared<StaticCollider>(tile(0, 0, 0)));
    std::vector<TriangleRef> refs;
    const Aabb box{{-1, -1, -1}, {5, 1, 5}};
    world.query_aabb(box, refs);
    StaticWorld moved = std::move(world);
    refs.clear();
    moved.query_aabb(box, refs);
    EXPECT_EQ(refs.size(), 2u);
    world.add(std::make_shared<StaticCollider>(tile(0, 0, 0)));  // moved from: empty again
    refs.clear();
    world.query_aabb(box, refs);
    EXPECT_EQ(refs.size(), 2u);
}

}  // namespace
}  // namespace trackphys
