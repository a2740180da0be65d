// PlaneTreeFrameCache: the frames it hands out are the trees' own, built once until
// clear(), and stay where they are while it grows; MidPhase candidates keep pointing at
// valid frames when an update's box is widened.
#include "trackphys/collision/plane_tree_frame_cache.hpp"

#include <cstdint>
#include <memory>
#include <vector>

#include <gtest/gtest.h>

#include "collision/collision_meshes.hpp"
#include "trackphys/collision/mid_phase.hpp"
#include "trackphys/collision/plane_tree.hpp"
#include "trackphys/collision/static_collider.hpp"
#include "trackphys/collision/static_world.hpp"

namespace trackphys {
namespace {

void expect_same_frame(const NormalizedTriangle& a, const NormalizedTriangle& b) {
    EXPECT_EQ(a.origin, b.origin);
    EXPECT_EQ(a.dir_x, b.dir_x);
    EXPECT_EQ(a.dir_y, b.dir_y);
    EXPECT_EQ(a.normal, b.normal);
    EXPECT_EQ(a.x1, b.x1);
    EXPECT_EQ(a.x2, b.x2);
    EXPECT_EQ(a.y2, b.y2);
}

TEST(PlaneTreeFrameCache, FramesAreTheTreesOwnBuiltOnceAndStayPut) {
    const StaticCollider collider(test::random_soup(3000, 5));
    const PlaneTree trees[] = {make_collider_plane_tree(collider),
                               make_collider_plane_tree(collider)};
    PlaneTreeFrameCache cache;
    std::vector<const NormalizedTriangle*> first;
    for (const PlaneTree& tree : trees)
        for (std::uint32_t slot = 0; slot < tree.triangle_count(); ++slot) {
            first.push_back(&cache.frame(tree, slot));
            expect_same_frame(*first.back(), tree.triangle(slot));
        }
    // 6000 frames made it grow many times; asking again gives the same addresses, and two
    // trees over one collider keep frames apart.
    std::size_t k = 0;
    for (const PlaneTree& tree : trees)
        for (std::uint32_t slot = 0; slot < tree.triangle_count(); ++slot, ++k)
            ASSERT_EQ(&cache.frame(tree, slot), first[k]);
    EXPECT_NE(&cache.frame(trees[0], 7), &cache.frame(trees[1], 7));
    // After clear() the storage is reused: frames are built anew, still the right ones.
    cache.clear();
    for (std::uint32_t slot = 0; slot < 100; ++slot)
        expect_same_frame(cache.frame(trees[1], slot), trees[1].triangle(slot));
}

TEST(PlaneTreeFrameCache, CandidatesSurviveAWidenedUpdate) {
    auto world = std::make_shared<StaticWorld>();
    world->add(std::make_shared<const StaticCollider>(test::random_soup(3000, 6)));
    MidPhase mid(MidPhaseMode::precomputed_tree, *world, make_collider_plane_trees(*world));
    const glm::dvec3 center = world->collider(0).triangle(0)[0];
    Aabb box;
    box.expand(center - glm::dvec3(3.0));
    box.expand(center + glm::dvec3(3.0));
    mid.begin_update(box);
    std::vector<MidPhaseCandidate> before;
    mid.query_swept_sphere(center, center + glm::dvec3(0.5, 0.0, 0.0), 1.5, before);
    ASSERT_FALSE(before.empty());
    // World widens the box mid-step and queries elsewhere (frames that would overwrite
    // `before`'s if the storage were reused), still culling with `before`.
    std::vector<MidPhaseCandidate> after;
    for (std::uint32_t t = 1; t < 3000 && after.size() < 50; t += 7) {
        const glm::dvec3 at = world->collider(0).triangle(t)[1];
        box.expand(at - glm::dvec3(2.0));
        box.expand(at + glm::dvec3(2.0));
        mid.begin_update(box);
        mid.query_swept_sphere(at, at, 1.0, after);
    }
    ASSERT_GE(after.size(), 50u);
    for (const MidPhaseCandidate& c : before)
        expect_same_frame(*c.triangle, world->collider(0).normalized_triangle(c.ref.triangle));
}

}  // namespace
}  // namespace trackphys
