// MidPhase on the default track: every mode returns a superset of the triangles each car
// ellipsoid's swept shape truly touches (long-double reference), the tree modes return
// exactly those, and the per-update and precomputed trees agree triangle for triangle.
#include <algorithm>
#include <cstdint>
#include <cstring>
#include <memory>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

#include "collision/plane_tree_reference.hpp"
#include "trackphys/collision/mid_phase.hpp"
#include "trackphys/collision/static_world.hpp"
#include "trackphys/dynamics/car_spec.hpp"
#include "trackphys/error.hpp"
#include "trackphys/track/track.hpp"
#include "trackphys/track/track_stats.hpp"

namespace trackphys {
namespace {

constexpr long double kLimitTolerance = 1e-9L;

struct TrackWorld {
    Track track;
    StaticWorld world;
    ColliderPlaneTrees trees;
};

const TrackWorld& track_world() {
    static const TrackWorld instance = [] {
        TrackWorld w;
        TrackParams params;
        params.seed = 7;
        w.track = generate_track(params);
        for (const TrackChunk& chunk : w.track.chunks)
            w.world.add(std::make_shared<const StaticCollider>(chunk.mesh));
        w.trees = make_collider_plane_trees(w.world);
        return w;
    }();
    return instance;
}

/// One step of one ellipsoid: its bounding sphere or itself, swept from start to end.
struct StepShape {
    Ellipsoid ellipsoid;
    glm::dvec3 end;
    double margin;
    bool as_sphere;

    double radius() const { return ellipsoid.bounding_radius(); }
    double scale() const { return 1.0 + margin / ellipsoid.sorted_radii().z; }
    Aabb box() const {
        Aabb b;
        b.expand(ellipsoid.center());
        b.expand(end);
        return b.padded(as_sphere ? radius() : radius() * scale());
    }
    long double limit() const { return as_sphere ? (long double)radius() : 1.0L; }
    long double distance(const Triangle& t) const {
        return as_sphere ? test::swept_sphere_distance(ellipsoid.center(), end, t)
                         : test::swept_ellipsoid_distance(ellipsoid, scale(), end, t);
    }
    void query(MidPhase& mid, std::vector<MidPhaseCandidate>& out) const {
        if (as_sphere)
            mid.query_swept_sphere(ellipsoid.center(), end, radius(), out);
        else
            mid.query_swept_ellipsoid(ellipsoid, end, margin, out);
    }
};

std::vector<TriangleRef> refs_of(const std::vector<MidPhaseCandidate>& list) {
    std::vector<TriangleRef> refs;
    for (const MidPhaseCandidate& c : list) refs.push_back(c.ref);
    std::sort(refs.begin(), refs.end());
    return refs;
}

TEST(MidPhase, EveryModeKeepsWhatTheCarTouchesOnTheDefaultTrack) {
    const TrackWorld& w = track_world();
    const CarSpec car = CarSpec::default_car();
    const MidPhaseMode modes[] = {MidPhaseMode::none, MidPhaseMode::per_update_tree,
                                  MidPhaseMode::precomputed_tree};
    std::vector<std::unique_ptr<MidPhase>> mids;
    for (const MidPhaseMode mode : modes)
        mids.push_back(std::make_unique<MidPhase>(
            mode, w.world,
            mode == MidPhaseMode::precomputed_tree ? w.trees : ColliderPlaneTrees{}));

    std::mt19937_64 rng(3);
    std::uniform_int_distribution<std::size_t> sample(0, w.track.centerline.size() - 1);
    std::uniform_real_distribution<double> lateral(-2.0, 2.0), lift(-0.12, 0.15), tilt(-0.08, 0.08);
    std::vector<std::size_t> samples{compute_track_stats(w.track).tightest_sample};
    for (int i = 0; i < 40; ++i) samples.push_back(sample(rng));

    std::size_t touched = 0, tree_candidates = 0;
    std::vector<MidPhaseCandidate> lists[3];
    std::vector<TriangleRef> near;
    for (const std::size_t s : samples) {
        const CenterlineSample& c = w.track.centerline[s];
        // The car's update box at the centre line, grown by the 2 m it may sit off it and the
        // bounding spheres of its ellipsoids.
        const Aabb update_box = car_update_box(c).padded(3.5);
        for (auto& mid : mids) mid->begin_update(update_box);
        // The car off the centre line, a little high or low (0.64 m is resting), slightly
        // rolled, one 1 ms step at 1000 km/h.
        // One draw a statement: the order of two draws in one expression is the compiler's.
        const double across = lateral(rng);
        const double rise = lift(rng);
        const double roll = tilt(rng);
        const glm::dvec3 origin = c.position + c.left * across + c.up * (0.64 + rise);
        const glm::dquat body =
            glm::angleAxis(roll, c.tangent) * glm::quat_cast(glm::dmat3(c.left, c.up, c.tangent));
        const glm::dvec3 step = c.tangent * (1000.0 / 3.6 * 0.001);
        for (const CarEllipsoid& ce : car.ellipsoids) {
            const glm::dvec3 center = origin + body * ce.center;
            for (const bool as_sphere : {true, false}) {
                const StepShape shape{Ellipsoid(center, body * ce.orientation, ce.semi_axes),
                                      center + step, 0.02, as_sphere};
                const Aabb box = shape.box();
                ASSERT_TRUE(update_box.contains(box.min) && update_box.contains(box.max))
                    << "test shapes must lie in the update box";
                for (int m = 0; m < 3; ++m) {
                    lists[m].clear();
                    shape.query(*mids[std::size_t(m)], lists[m]);
                }
                EXPECT_EQ(lists[0].size(), mids[0]->broad_phase_candidate_count());
                // The two trees run the same filter on the same frames: the same triangles.
                ASSERT_EQ(refs_of(lists[1]), refs_of(lists[2]));
                tree_candidates += lists[2].size();
                for (const MidPhaseCandidate& cand : lists[2]) {
                    const StaticCollider& collider = w.world.collider(cand.ref.collider);
                    EXPECT_EQ(cand.triangle->origin,
                              collider.normalized_triangle(cand.ref.triangle).origin);
                    EXPECT_LE(shape.distance(collider.triangle(cand.ref.triangle)),
                              shape.limit() + kLimitTolerance);
                }
                // Ground truth over every triangle near the shape.
                near.clear();
                w.world.query_aabb(box, near);
                const std::vector<TriangleRef> none = refs_of(lists[0]);
                const std::vector<TriangleRef> tree = refs_of(lists[2]);
                for (const TriangleRef& ref : near) {
                    const Triangle t = w.world.collider(ref.collider).triangle(ref.triangle);
                    if (shape.distance(t) > shape.limit() - kLimitTolerance) continue;
                    ++touched;
                    EXPECT_TRUE(std::binary_search(none.begin(), none.end(), ref));
                    EXPECT_TRUE(std::binary_search(tree.begin(), tree.end(), ref))
                        << "collider " << ref.collider << " triangle " << ref.triangle;
                }
            }
        }
    }
    // The wheels meet the road at every sample; the bounding spheres reach much more.
    EXPECT_GT(touched, samples.size() * 4 * 2);
    EXPECT_GT(tree_candidates, touched / 2);
    const MidPhaseCounters& counters = mids[2]->counters();
    EXPECT_EQ(counters.updates, samples.size());
    EXPECT_EQ(counters.queries, samples.size() * car.ellipsoids.size() * 2);
    EXPECT_EQ(counters.candidates, tree_candidates);
    EXPECT_GT(counters.planes_tested, counters.queries);
}

TEST(MidPhase, CollidersPlaneTreesAreTheSameOnAnyThreadCount) {
    StaticWorld world;
    for (std::size_t i = 0; i < 6; ++i)
        world.add(std::make_shared<const StaticCollider>(track_world().track.chunks[i].mesh));
    const ColliderPlaneTrees one =
        make_collider_plane_trees(world, PlaneTreeSettings::precomputed(), 1);
    const ColliderPlaneTrees three =
        make_collider_plane_trees(world, PlaneTreeSettings::precomputed(), 3);
    ASSERT_EQ(one.size(), world.size());
    ASSERT_EQ(three.size(), world.size());
    for (std::size_t id = 0; id < world.size(); ++id) {
        const PlaneTree &a = *one[id], &b = *three[id];
        ASSERT_EQ(a.nodes().size(), b.nodes().size()) << id;
        EXPECT_EQ(std::memcmp(a.nodes().data(), b.nodes().data(),
                              a.nodes().size() * sizeof(PlaneTreeNode)),
                  0)
            << id;
        ASSERT_EQ(a.triangle_count(), b.triangle_count()) << id;
        for (std::uint32_t slot = 0; slot < a.triangle_count(); ++slot)
            ASSERT_EQ(a.id(slot), b.id(slot)) << id;
    }
}

TEST(MidPhase, PrecomputedModeNeedsOneTreePerCollider) {
    const TrackWorld& w = track_world();
    ColliderPlaneTrees fewer(w.trees.begin(), w.trees.end() - 1);
    EXPECT_THROW(MidPhase(MidPhaseMode::precomputed_tree, w.world, fewer), Error);
    ColliderPlaneTrees with_null = w.trees;
    with_null[3] = nullptr;
    EXPECT_THROW(MidPhase(MidPhaseMode::precomputed_tree, w.world, with_null), Error);
    EXPECT_NO_THROW(MidPhase(MidPhaseMode::none, w.world));
    const auto shared_null = std::make_shared<const ColliderPlaneTrees>(std::move(with_null));
    EXPECT_THROW(MidPhase(MidPhaseMode::precomputed_tree, w.world, shared_null), Error);
    EXPECT_THROW(MidPhase(MidPhaseMode::precomputed_tree, w.world,
                          std::shared_ptr<const ColliderPlaneTrees>{}),
                 Error);
    EXPECT_NO_THROW(MidPhase(MidPhaseMode::none, w.world, shared_null));
}

TEST(MidPhase, AColliderAddedSinceTheTreesStopsTheNextUpdate) {
    StaticWorld world;
    const std::vector<TrackChunk>& chunks = track_world().track.chunks;
    for (std::size_t i = 0; i < 3; ++i)
        world.add(std::make_shared<const StaticCollider>(chunks[i].mesh));
    const auto trees = std::make_shared<const ColliderPlaneTrees>(make_collider_plane_trees(world));
    MidPhase first(MidPhaseMode::precomputed_tree, world, trees);
    MidPhase second(MidPhaseMode::precomputed_tree, world, trees);
    const Aabb box = car_update_box(track_world().track.centerline[0]);
    EXPECT_NO_THROW(first.begin_update(box));
    world.add(std::make_shared<const StaticCollider>(chunks[3].mesh));
    EXPECT_THROW(first.begin_update(box), Error);
    EXPECT_THROW(second.begin_update(box), Error);
}

TEST(MidPhase, QueriesRejectBadInputInEveryMode) {
    const TrackWorld& w = track_world();
    std::vector<MidPhaseCandidate> out;
    for (const MidPhaseMode mode :
         {MidPhaseMode::none, MidPhaseMode::per_update_tree, MidPhaseMode::precomputed_tree}) {
        MidPhase mid(mode, w.world,
                     mode == MidPhaseMode::precomputed_tree ? w.trees : ColliderPlaneTrees{});
        mid.begin_update(car_update_box(w.track.centerline[0]));
        EXPECT_THROW(mid.query_swept_sphere({0, 0, 0}, {0, 0, 0}, -1.0, out), Error);
        const Ellipsoid e(w.track.centerline[0].position, {1, 0, 0, 0}, {1, 1, 1});
        EXPECT_THROW(mid.query_swept_ellipsoid(e, e.center(), -0.5, out), Error);
    }
}

TEST(MidPhase, ModeNamesRoundTrip) {
    for (const MidPhaseMode mode :
         {MidPhaseMode::none, MidPhaseMode::per_update_tree, MidPhaseMode::precomputed_tree})
        EXPECT_EQ(parse_mid_phase_mode(to_string(mode)), mode);
    EXPECT_FALSE(parse_mid_phase_mode("bvh").has_value());
}

}  // namespace
}  // namespace trackphys
