// The mid phase's filter in lanes (plane_tree.cpp's filter_in_lanes: a query's leaf slots
// batched 64 at a time across leaves, each batch filtered N frames at a time with a short
// last block repeating its last frame, the kept slots compacted in place) against the
// per-slot filter of filter_leaf on the same queries. A tree that keeps its frames filters
// in lanes; the same collider's tree that builds them filters slot by slot. The test runs in
// four lanes on an AVX2 machine and again in two (twolanes., TRACKPHYS_LANES=2).
#include <cmath>
#include <cstdint>
#include <random>
#include <set>
#include <vector>

#include <gtest/gtest.h>

#include <glm/gtc/quaternion.hpp>

#include "support/grid_mesh.hpp"
#include "trackphys/collision/plane_tree.hpp"
#include "trackphys/collision/plane_tree_frame_cache.hpp"
#include "trackphys/collision/static_collider.hpp"

namespace trackphys {
namespace {

// A bumpy square of ground, 48 m a side in 1 m cells of two triangles: a query a few metres
// wide reaches more than a batch of 64 slots.
TriangleMesh bumpy_ground() {
    constexpr int kCells = 48;
    return test::grid_mesh(kCells, kCells, [](int i, int j) {
        return glm::dvec3(i, j, 0.3 * std::sin(0.7 * i) * std::cos(0.5 * j));
    });
}

TEST(PlaneTreeLanes, SweptEllipsoidsKeepWhatTheLeafFilterKeeps) {
    const StaticCollider collider(bumpy_ground());
    std::mt19937_64 rng(2026);
    std::uniform_real_distribution<double> across(4.0, 44.0), height(-0.5, 2.0), sym(-1.0, 1.0),
        size(0.2, 5.0);
    std::set<std::size_t> tails;
    std::size_t batched_past_64 = 0, kept = 0, dropped = 0;
    for (int leaf_size : {1, 3, 4, 5, 17, 64}) {
        PlaneTreeSettings settings = PlaneTreeSettings::per_update();
        settings.max_leaf_size = leaf_size;
        const PlaneTree lanes = make_collider_plane_tree(collider, settings, PlaneTreeFrames::kept);
        const PlaneTree per_slot =
            make_collider_plane_tree(collider, settings, PlaneTreeFrames::built);
        ASSERT_TRUE(lanes.keeps_frames());
        ASSERT_FALSE(per_slot.keeps_frames());
        PlaneTreeFrameCache cache;
        for (int i = 0; i < 300; ++i) {
            const glm::dvec3 at(across(rng), across(rng), height(rng));
            const glm::dvec3 to = at + glm::dvec3(sym(rng), sym(rng), 0.2 * sym(rng));
            const double r = size(rng);
            const glm::dquat turn = glm::normalize(glm::dquat(1.0, sym(rng), sym(rng), sym(rng)));
            const Ellipsoid e(at, turn, glm::dvec3(r, 0.6 * r, 0.25 * r));
            std::vector<std::uint32_t> from_lanes, from_slots, from_cache;
            const PlaneTreeQueryCounts counts =
                lanes.query_swept_ellipsoid(e, to, 0.01, from_lanes);
            const PlaneTreeQueryCounts slot_counts =
                per_slot.query_swept_ellipsoid(e, to, 0.01, from_slots);
            per_slot.query_swept_ellipsoid(e, to, 0.01, from_cache, 0, &cache);
            ASSERT_EQ(from_lanes, from_slots) << "leaves of " << leaf_size << ", query " << i;
            ASSERT_EQ(from_cache, from_slots) << "leaves of " << leaf_size << ", query " << i;
            EXPECT_EQ(counts.triangles_filtered, slot_counts.triangles_filtered);
            tails.insert(counts.triangles_filtered % 4);
            if (counts.triangles_filtered > 64) ++batched_past_64;
            kept += from_lanes.size();
            dropped += counts.triangles_filtered - from_lanes.size();
        }
    }
    // Every tail of a block of four, many queries of more than one batch, and the filter
    // both keeping and dropping slots.
    EXPECT_EQ(tails.size(), 4u);
    EXPECT_GT(batched_past_64, 300u);
    EXPECT_GT(kept, 10000u);
    EXPECT_GT(dropped, 10000u);
}

}  // namespace
}  // namespace trackphys
