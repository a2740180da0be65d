// PlaneTreeFrameCache: the frames it hands out are the trees' own, built once until
// clear(), and stay where they are while it grows; MidPhase candidates keep pointing at
// valid frames when an update's box is widened. Trees that keep their frames (within a
// world's frame budget) report the same and leave the cache unused.
#include "trackphys/collision/plane_tree_frame_cache.hpp"

#include <algorithm>
#include <cstdint>
#include <memory>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include <glm/gtc/quaternion.hpp>

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

// Each leaf of `tree` as the runs PlaneTree queries ask the cache for.
struct LeafRun {
    std::uint32_t first, count;
};
std::vector<LeafRun> leaf_runs(const PlaneTree& tree) {
    std::vector<LeafRun> runs;
    for (const PlaneTreeNode& node : tree.nodes())
        if (node.is_leaf())
            for (std::uint32_t first = node.first; first < node.first + node.count();
                 first += PlaneTreeFrameCache::kMaxRun)
                runs.push_back({first, std::min(node.first + node.count() - first,
                                                PlaneTreeFrameCache::kMaxRun)});
    return runs;
}

std::uint64_t all_of(std::uint32_t count) {
    return count == 64 ? ~std::uint64_t{0} : (std::uint64_t{1} << count) - 1;
}

TEST(PlaneTreeFrameCache, FramesAreTheTreesOwnBuiltOnceAndStayPut) {
    const StaticCollider collider(test::random_soup(3000, 5));
    const PlaneTree trees[] = {make_collider_plane_tree(collider),
                               make_collider_plane_tree(collider)};
    PlaneTreeFrameCache cache;
    std::vector<const NormalizedTriangle*> first;
    for (const PlaneTree& tree : trees)
        for (const LeafRun& run : leaf_runs(tree)) {
            // Half the slots at first (the odd ones), the others on the second call.
            const std::uint64_t odd = all_of(run.count) & 0xaaaa'aaaa'aaaa'aaaaull;
            const NormalizedTriangle* frames = cache.run(tree, run.first, run.count, odd);
            ASSERT_EQ(cache.run(tree, run.first, run.count, all_of(run.count)), frames);
            for (std::uint32_t k = 0; k < run.count; ++k) {
                first.push_back(frames + k);
                expect_same_frame(frames[k], tree.triangle(run.first + k));
            }
        }
    // 6000 frames made it grow many times; asking again gives the same addresses, and two
    // trees over one collider keep frames apart.
    std::size_t k = 0;
    for (const PlaneTree& tree : trees)
        for (const LeafRun& run : leaf_runs(tree))
            for (std::uint32_t i = 0; i < run.count; ++i, ++k)
                ASSERT_EQ(cache.run(tree, run.first, run.count, std::uint64_t{1} << i) + i,
                          first[k]);
    const LeafRun some = leaf_runs(trees[0])[3];
    EXPECT_NE(cache.run(trees[0], some.first, some.count, 1),
              cache.run(trees[1], some.first, some.count, 1));
    // After clear() the storage is reused: frames are built anew, still the right ones.
    cache.clear();
    for (const LeafRun& run : leaf_runs(trees[1])) {
        const NormalizedTriangle* frames = cache.run(trees[1], run.first, run.count, 1);
        expect_same_frame(frames[0], trees[1].triangle(run.first));
    }
}

// Queries through a cache report the slots they report without one, and reported() holds
// those slots' frames; one cache serves every query (frames built by earlier ones are
// reused), cleared now and then. Leaves of up to 64 slots use the run's every mask bit.
TEST(PlaneTreeFrameCache, QueriesThroughTheCacheReportTheSameSlotsAndTheirFrames) {
    const StaticCollider collider(test::random_soup(4096, 9));
    PlaneTreeSettings big_leaves = PlaneTreeSettings::per_update();
    big_leaves.max_leaf_size = 64;
    std::mt19937_64 rng(10);
    std::uniform_int_distribution<std::uint32_t> pick(
        0, static_cast<std::uint32_t>(collider.triangle_count() - 1));
    std::uniform_real_distribution<double> sym(-1.0, 1.0), radius(0.05, 3.0);
    for (const PlaneTreeSettings& settings : {PlaneTreeSettings::precomputed(), big_leaves}) {
        const PlaneTree tree = make_collider_plane_tree(collider, settings);
        std::uint32_t largest_leaf = 0;
        for (const PlaneTreeNode& node : tree.nodes())
            if (node.is_leaf()) largest_leaf = std::max(largest_leaf, node.count());
        if (settings.max_leaf_size == 64) {
            EXPECT_GT(largest_leaf, 32u);
        }
        PlaneTreeFrameCache cache;
        std::size_t reported = 0;
        for (int i = 0; i < 600; ++i) {
            if (i % 50 == 0) cache.clear();
            const glm::dvec3 at =
                tree.triangle(pick(rng)).vertex(0) + glm::dvec3(sym(rng), sym(rng), sym(rng)) * 0.5;
            const glm::dvec3 to = at + glm::dvec3(sym(rng), sym(rng), sym(rng));
            const double r = radius(rng);
            std::vector<std::uint32_t> plain, cached;
            if (i % 3 == 0) {
                tree.query_sphere(at, r, plain);
                tree.query_sphere(at, r, cached, 0, &cache);
            } else if (i % 3 == 1) {
                tree.query_swept_sphere(at, to, r, plain);
                tree.query_swept_sphere(at, to, r, cached, 0, &cache);
            } else {
                const Ellipsoid e(at, glm::dquat(1, 0, 0, 0), glm::dvec3(r, 0.5 * r, 0.3 * r));
                tree.query_swept_ellipsoid(e, to, 0.01, plain);
                tree.query_swept_ellipsoid(e, to, 0.01, cached, 0, &cache);
            }
            ASSERT_EQ(cached, plain);
            ASSERT_EQ(cache.reported().size(), cached.size());
            for (std::size_t k = 0; k < cached.size(); ++k)
                expect_same_frame(*cache.reported()[k], tree.triangle(cached[k]));
            reported += cached.size();
        }
        EXPECT_GT(reported, 300u);  // most queries report something
    }
}

// A tree that keeps its frames reports what the tree that builds them reports, frame for
// frame, reads them in place (the cache stays empty) and points reported() at its own.
TEST(PlaneTreeFrameCache, TreesThatKeepTheirFramesReportTheSameWithoutTheCache) {
    const StaticCollider collider(test::random_soup(4096, 12));
    const PlaneTree built = make_collider_plane_tree(collider, PlaneTreeSettings::precomputed(),
                                                     PlaneTreeFrames::built);
    const PlaneTree kept =
        make_collider_plane_tree(collider, PlaneTreeSettings::precomputed(), PlaneTreeFrames::kept);
    EXPECT_FALSE(built.keeps_frames());
    EXPECT_TRUE(kept.keeps_frames());
    EXPECT_GT(kept.bytes_used(), built.bytes_used() + 90 * collider.triangle_count());
    std::mt19937_64 rng(13);
    std::uniform_int_distribution<std::uint32_t> pick(
        0, static_cast<std::uint32_t>(collider.triangle_count() - 1));
    std::uniform_real_distribution<double> sym(-1.0, 1.0), radius(0.05, 3.0);
    PlaneTreeFrameCache built_cache, kept_cache;
    std::size_t reported = 0;
    for (int i = 0; i < 400; ++i) {
        const glm::dvec3 at =
            built.triangle(pick(rng)).vertex(0) + glm::dvec3(sym(rng), sym(rng), sym(rng)) * 0.5;
        const glm::dvec3 to = at + glm::dvec3(sym(rng), sym(rng), sym(rng));
        const double r = radius(rng);
        std::vector<std::uint32_t> from_built, from_kept, plain;
        if (i % 2 == 0) {
            built.query_swept_sphere(at, to, r, from_built, 0, &built_cache);
            kept.query_swept_sphere(at, to, r, from_kept, 0, &kept_cache);
            kept.query_swept_sphere(at, to, r, plain);
        } else {
            const Ellipsoid e(at, glm::dquat(1, 0, 0, 0), glm::dvec3(r, 0.5 * r, 0.3 * r));
            built.query_swept_ellipsoid(e, to, 0.01, from_built, 0, &built_cache);
            kept.query_swept_ellipsoid(e, to, 0.01, from_kept, 0, &kept_cache);
            kept.query_swept_ellipsoid(e, to, 0.01, plain);
        }
        ASSERT_EQ(from_kept, from_built);
        ASSERT_EQ(plain, from_built);
        ASSERT_EQ(kept_cache.reported().size(), from_kept.size());
        for (std::size_t k = 0; k < from_kept.size(); ++k) {
            expect_same_frame(*kept_cache.reported()[k], *built_cache.reported()[k]);
            const NormalizedTriangle kept_frame = kept.triangle(from_kept[k]);
            expect_same_frame(*kept_cache.reported()[k], kept_frame);
        }
        reported += from_kept.size();
    }
    EXPECT_GT(reported, 200u);
    // No frame block (1024 frames) and no index (4096 entries): only reported()'s pointers.
    EXPECT_LT(kept_cache.bytes_used(), 64 * sizeof(NormalizedTriangle));
    EXPECT_GT(built_cache.bytes_used(), 1024 * sizeof(NormalizedTriangle));
}

// A world's trees keep their frames while the frames fit the budget, to the byte.
TEST(PlaneTreeFrameCache, AWorldsTreesKeepTheirFramesWithinTheBudget) {
    auto world = std::make_shared<StaticWorld>();
    world->add(std::make_shared<const StaticCollider>(test::random_soup(700, 14)));
    world->add(std::make_shared<const StaticCollider>(test::random_soup(300, 15)));
    const std::size_t triangles =
        world->collider(0).triangle_count() + world->collider(1).triangle_count();
    const std::size_t fits = triangles * sizeof(NormalizedTriangle);
    const auto keeps = [&](std::size_t budget) {
        const ColliderPlaneTrees trees =
            make_collider_plane_trees(*world, PlaneTreeSettings::precomputed(), 1, budget);
        EXPECT_EQ(trees[0]->keeps_frames(), trees[1]->keeps_frames());
        return trees[0]->keeps_frames();
    };
    EXPECT_TRUE(keeps(fits));
    EXPECT_FALSE(keeps(fits - 1));
    EXPECT_FALSE(keeps(0));
    EXPECT_TRUE(keeps(kPlaneTreeFrameBudget));
    EXPECT_EQ(plane_tree_frames_within(0, 0), PlaneTreeFrames::kept);
    EXPECT_EQ(plane_tree_frames_within(10'000'000, kPlaneTreeFrameBudget), PlaneTreeFrames::built);
}

TEST(PlaneTreeFrameCache, CandidatesSurviveAWidenedUpdate) {
    auto world = std::make_shared<StaticWorld>();
    world->add(std::make_shared<const StaticCollider>(test::random_soup(3000, 6)));
    // No frame budget: the trees build their frames into the MidPhase's cache.
    MidPhase mid(MidPhaseMode::precomputed_tree, *world,
                 make_collider_plane_trees(*world, PlaneTreeSettings::precomputed(), 1, 0));
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
