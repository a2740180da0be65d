#include "midphase_scene.hpp"

#include "trackphys/geometry/contact.hpp"
#include "trackphys/geometry/ellipsoid_cull.hpp"

namespace trackphys::bench {

MidScene::MidScene() {
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

    for (int sub = 0; sub < TightestTurnScene::kSubsteps; ++sub)
        for (std::size_t e = 0; e < s.car.ellipsoids.size(); ++e)
            placed.push_back(s.ellipsoid(e, sub));
    constexpr int kSteps = TightestTurnScene::kSubsteps / TightestTurnScene::kStepSubsteps;
    for (int step = 0; step < kSteps; ++step) {
        const int first = step * TightestTurnScene::kStepSubsteps;
        for (std::size_t e = 0; e < s.car.ellipsoids.size(); ++e)
            queries.push_back({s.center(e, first),
                               s.center(e, first + TightestTurnScene::kStepSubsteps),
                               s.bounding_radius(e), s.ellipsoid(e, first)});
    }
}

const MidScene& mid_scene() {
    static const MidScene instance;
    return instance;
}

std::unique_ptr<MidPhase> make_mid_phase(MidPhaseMode mode) {
    const MidScene& m = mid_scene();
    return std::make_unique<MidPhase>(
        mode, m.world, mode == MidPhaseMode::precomputed_tree ? m.trees : ColliderPlaneTrees{});
}

const std::vector<MidVariant>& mid_variants() {
    static const std::vector<MidVariant> variants = {
        {MidPhaseMode::per_update_tree, Shape::sphere, 1, "write-up: per-update PCA tree, spheres",
         "the write-up's WIP, queried every step: ~1.25 ms to build there"},
        {MidPhaseMode::none, Shape::ellipsoid, 1, "none",
         "every ellipsoid scans the broad-phase list"},
        {MidPhaseMode::per_update_tree, Shape::ellipsoid, 1, "per-update PCA tree, ellipsoids", ""},
        {MidPhaseMode::precomputed_tree, Shape::sphere, 1, "precomputed, spheres",
         "the write-up's swept spheres"},
        {MidPhaseMode::precomputed_tree, Shape::ellipsoid, 1, "precomputed, ellipsoids, every step",
         ""},
        {MidPhaseMode::precomputed_tree, Shape::ellipsoid, WorldSettings{}.mid_phase_look_ahead,
         "precomputed, ellipsoids, looking ahead", "ours: World's default"}};
    return variants;
}

namespace {

// One update's lists as World builds them (see run_update): calls visit(step, ellipsoid,
// list) with each step's list of each ellipsoid. Returns the list lengths summed.
template <class Visit>
std::size_t visit_lists(MidPhase& mid, const MidVariant& variant, UpdateLists& lists,
                        Visit&& visit) {
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
        visit(step, e, *list);
    }
    return total;
}

}  // namespace

std::size_t run_update(MidPhase& mid, const MidVariant& variant, SubstepCull cull,
                       UpdateLists& lists, std::size_t& kept) {
    const MidScene& m = mid_scene();
    const std::size_t ellipsoids = tightest_turn_scene().car.ellipsoids.size();
    return visit_lists(
        mid, variant, lists,
        [&](int step, std::size_t e, const std::vector<MidPhaseCandidate>& list) {
            if (cull == SubstepCull::none) return;
            const int first = step * TightestTurnScene::kStepSubsteps;
            for (int sub = first; sub < first + TightestTurnScene::kStepSubsteps; ++sub) {
                const Ellipsoid& placed = m.placed[std::size_t(sub) * ellipsoids + e];
                if (cull == SubstepCull::bounding_sphere) {
                    const double radius = m.queries[std::size_t(step) * ellipsoids + e].radius;
                    for (const MidPhaseCandidate& cand : list)
                        kept += cand.triangle->may_touch_sphere(placed.center(), radius) ? 1 : 0;
                } else {
                    for (const MidPhaseCandidate& cand : list)
                        kept += ellipsoid_depth_bound(*cand.triangle, placed) > 0.0 ? 1 : 0;
                }
            }
        });
}

std::vector<ListEntry> touching_in_lists(MidPhase& mid, const MidVariant& variant,
                                         UpdateLists& lists) {
    const MidScene& m = mid_scene();
    const std::size_t ellipsoids = tightest_turn_scene().car.ellipsoids.size();
    std::vector<ListEntry> touching;
    visit_lists(mid, variant, lists,
                [&](int step, std::size_t e, const std::vector<MidPhaseCandidate>& list) {
                    const int first = step * TightestTurnScene::kStepSubsteps;
                    for (int sub = first; sub < first + TightestTurnScene::kStepSubsteps; ++sub) {
                        const Ellipsoid& placed = m.placed[std::size_t(sub) * ellipsoids + e];
                        for (const MidPhaseCandidate& cand : list) {
                            const Triangle triangle =
                                m.world.collider(cand.ref.collider).triangle(cand.ref.triangle);
                            if (ellipsoid_triangle_contact(placed, triangle).depth > 0.0)
                                touching.push_back({sub, e, cand.ref});
                        }
                    }
                });
    std::sort(touching.begin(), touching.end());
    touching.erase(std::unique(touching.begin(), touching.end()), touching.end());
    return touching;
}

double tested_per_ellipsoid_substep(std::size_t total_per_update) {
    return double(total_per_update) / double(mid_scene().queries.size());
}

}  // namespace trackphys::bench
