#pragma once

// The mid phase on the default track's tightest banked turn at 1000 km/h
// (tightest_turn_scene.hpp), header-only, shared by bench_midphase and `trackphys bench`:
// the track's colliders and precomputed plane trees, each step's query per ellipsoid (10
// steps x 8 ellipsoids), and one update's mid-phase work in each variant (mode, query shape,
// look-ahead).

#include <algorithm>
#include <chrono>
#include <cstddef>
#include <memory>
#include <vector>

#include "tightest_turn_scene.hpp"
#include "trackphys/collision/look_ahead_list.hpp"
#include "trackphys/collision/mid_phase.hpp"
#include "trackphys/detail/plane_tree_builder.hpp"
#include "trackphys/collision/static_world.hpp"
#include "trackphys/world/world_settings.hpp"

namespace trackphys::bench {

/// What each step queries with: the ellipsoid's swept bounding sphere or the swept
/// ellipsoid itself (as World does).
enum class Shape { sphere, ellipsoid };

/// How far a point of the car can move beyond the translation in one 1 ms step: the car
/// turns at v / R = 278 / 26 = 10.7 rad/s, 0.011 rad a step, times the 1.9 m floor pan.
constexpr double kRotationMargin = 0.02;

struct StepQuery {
    glm::dvec3 start, end;
    double radius;
    Ellipsoid ellipsoid;
};

/// The default track as colliders (one per chunk), their precomputed trees and the
/// tightest turn's step queries. Built once, on first use.
struct MidScene {
    StaticWorld world;
    ColliderPlaneTrees trees;             // cost_based (the precomputed default)
    std::uint32_t turn_collider = 0;      // the collider with most candidates
    std::vector<StepQuery> queries;       // 10 steps x 8 ellipsoids
    double trees_build_ms = 0.0;
    std::size_t trees_bytes = 0;

    MidScene() {
        const TightestTurnScene& s = tightest_turn_scene();
        for (const TrackChunk& chunk : s.track.chunks)
            world.add(std::make_shared<const StaticCollider>(chunk.mesh));
        const auto t0 = std::chrono::steady_clock::now();
        trees = make_collider_plane_trees(world);
        trees_build_ms =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
        for (const auto& tree : trees) trees_bytes += tree->bytes_used();

        std::vector<TriangleRef> refs;
        world.query_aabb(s.update_box, refs);
        std::vector<std::size_t> per_collider(world.size(), 0);
        for (const TriangleRef& r : refs) ++per_collider[r.collider];
        turn_collider = static_cast<std::uint32_t>(
            std::max_element(per_collider.begin(), per_collider.end()) - per_collider.begin());

        constexpr int kSteps = TightestTurnScene::kSubsteps / TightestTurnScene::kStepSubsteps;
        for (int step = 0; step < kSteps; ++step) {
            const int first = step * TightestTurnScene::kStepSubsteps;
            for (std::size_t e = 0; e < s.car.ellipsoids.size(); ++e)
                queries.push_back({s.center(e, first),
                                   s.center(e, first + TightestTurnScene::kStepSubsteps),
                                   s.bounding_radius(e), s.ellipsoid(e, first)});
        }
    }
};

inline const MidScene& mid_scene() {
    static const MidScene instance;
    return instance;
}

inline std::unique_ptr<MidPhase> make_mid_phase(MidPhaseMode mode) {
    const MidScene& m = mid_scene();
    return std::make_unique<MidPhase>(mode, m.world,
                                      mode == MidPhaseMode::precomputed_tree ? m.trees
                                                                             : ColliderPlaneTrees{});
}

/// One way of running an update's mid phase: the mode, the query shape, and how many steps
/// an ellipsoid query covers (World's look-ahead; spheres are queried every step).
struct MidVariant {
    MidPhaseMode mode;
    Shape shape;
    int look_ahead;
    const char* name;
    const char* note;
};

/// The variants compared, the write-up's loop (the reference) first.
inline const std::vector<MidVariant>& mid_variants() {
    static const std::vector<MidVariant> variants = {
        {MidPhaseMode::per_update_tree, Shape::sphere, 1, "write-up: per-update PCA tree, spheres",
         "the write-up's WIP, queried every step: ~1.25 ms to build there"},
        {MidPhaseMode::none, Shape::ellipsoid, 1, "none", "every ellipsoid scans the broad-phase list"},
        {MidPhaseMode::per_update_tree, Shape::ellipsoid, 1, "per-update PCA tree, ellipsoids", ""},
        {MidPhaseMode::precomputed_tree, Shape::sphere, 1, "precomputed, spheres",
         "the write-up's swept spheres"},
        {MidPhaseMode::precomputed_tree, Shape::ellipsoid, 1, "precomputed, ellipsoids, every step",
         ""},
        {MidPhaseMode::precomputed_tree, Shape::ellipsoid, WorldSettings{}.mid_phase_look_ahead,
         "precomputed, ellipsoids, looking ahead", "ours: World's default"}};
    return variants;
}
inline constexpr std::size_t kWriteupVariant = 0;
inline constexpr std::size_t kDefaultVariant = 5;

/// What run_update fills: the step's list of each ellipsoid.
struct UpdateLists {
    std::vector<MidPhaseCandidate> spheres;  ///< a sphere query's list, this step
    std::vector<LookAheadList> ellipsoids;   ///< per ellipsoid, as World keeps them
};

/// One update's mid-phase work as World does it: begin_update, then per step each
/// ellipsoid's list: its swept bounding sphere queried for the step, or its swept ellipsoid
/// through a LookAheadList that looks variant.look_ahead steps ahead (within the update, and
/// within the update box) and is reused while the step stays inside. With `cull`, also each
/// sub-step's bounding-sphere cull over the step's list (the loop's next stage), so the time
/// shows what the lists cost downstream. Returns the list lengths summed over the steps.
inline std::size_t run_update(MidPhase& mid, const MidVariant& variant, bool cull,
                              UpdateLists& lists, std::size_t& kept) {
    const TightestTurnScene& s = tightest_turn_scene();
    const MidScene& m = mid_scene();
    constexpr double kStepDt = TightestTurnScene::kSubstepDt * TightestTurnScene::kStepSubsteps;
    constexpr int kSteps = TightestTurnScene::kSubsteps / TightestTurnScene::kStepSubsteps;
    mid.begin_update(s.update_box);
    const std::size_t ellipsoids = s.car.ellipsoids.size();
    lists.ellipsoids.resize(ellipsoids);
    for (LookAheadList& list : lists.ellipsoids) list.forget();
    std::size_t total = 0;
    for (std::size_t q = 0; q < m.queries.size(); ++q) {
        const StepQuery& sq = m.queries[q];
        const std::size_t e = q % ellipsoids;
        const int step = int(q / ellipsoids);
        const std::vector<MidPhaseCandidate>* list = &lists.spheres;
        if (variant.shape == Shape::sphere) {
            lists.spheres.clear();
            mid.query_swept_sphere(sq.start, sq.end, sq.radius, lists.spheres);
        } else {
            LookAheadList& ahead = lists.ellipsoids[e];
            const SweptEllipsoid step_shape{sq.ellipsoid, sq.end, kRotationMargin};
            if (!ahead.covers(step_shape)) {
                SweptEllipsoid wanted =
                    look_ahead(step_shape, (sq.end - sq.start) / kStepDt, kStepDt,
                               ahead.steps_ahead(variant.look_ahead, kSteps - step),
                               WorldSettings{}.mid_phase_slack);
                if (!s.update_box.contains(wanted.bounds())) wanted = step_shape;
                ahead.refill(mid, wanted);
            }
            list = &ahead.candidates();
        }
        total += list->size();
        if (!cull) continue;
        const int first = step * TightestTurnScene::kStepSubsteps;
        for (int sub = first; sub < first + TightestTurnScene::kStepSubsteps; ++sub) {
            const glm::dvec3 c = s.center(e, sub);
            for (const MidPhaseCandidate& cand : *list)
                kept += cand.triangle->may_touch_sphere(c, sq.radius) ? 1 : 0;
        }
    }
    return total;
}

inline double tested_per_ellipsoid_substep(std::size_t total_per_update) {
    // Each step's list is tested in each of its 4 sub-steps: average list length.
    return double(total_per_update) / double(mid_scene().queries.size());
}

}  // namespace trackphys::bench
