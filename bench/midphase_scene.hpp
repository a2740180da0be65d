#pragma once

// The mid phase on the default track's tightest banked turn at 1000 km/h
// (tightest_turn_scene.hpp), header-only, shared by bench_midphase and `trackphys bench`:
// the track's colliders and precomputed plane trees, each step's query per ellipsoid (10
// steps x 8 ellipsoids), and one update's mid-phase work in each MidPhaseMode.

#include <algorithm>
#include <chrono>
#include <cstddef>
#include <memory>
#include <vector>

#include "tightest_turn_scene.hpp"
#include "trackphys/collision/mid_phase.hpp"
#include "trackphys/collision/plane_tree_builder.hpp"
#include "trackphys/collision/static_world.hpp"

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

/// One update's mid-phase work: begin_update, then each step's query per ellipsoid. With
/// `cull`, also each sub-step's bounding-sphere cull over the step's list (the loop's next
/// stage), so the time shows what the lists cost downstream. Returns the candidates summed.
inline std::size_t run_update(MidPhase& mid, Shape shape, bool cull,
                       std::vector<MidPhaseCandidate>& list, std::size_t& kept) {
    const TightestTurnScene& s = tightest_turn_scene();
    const MidScene& m = mid_scene();
    mid.begin_update(s.update_box);
    std::size_t total = 0;
    const std::size_t ellipsoids = s.car.ellipsoids.size();
    for (std::size_t q = 0; q < m.queries.size(); ++q) {
        const StepQuery& sq = m.queries[q];
        list.clear();
        if (shape == Shape::sphere)
            mid.query_swept_sphere(sq.start, sq.end, sq.radius, list);
        else
            mid.query_swept_ellipsoid(sq.ellipsoid, sq.end, kRotationMargin, list);
        total += list.size();
        if (!cull) continue;
        const std::size_t e = q % ellipsoids;
        const int first = int(q / ellipsoids) * TightestTurnScene::kStepSubsteps;
        for (int sub = first; sub < first + TightestTurnScene::kStepSubsteps; ++sub) {
            const glm::dvec3 c = s.center(e, sub);
            for (const MidPhaseCandidate& cand : list)
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
