// Mid phase on the default track's tightest banked turn at 1000 km/h (tightest_turn_scene.hpp): per
// update, the triangles each ellipsoid tests per sub-step and the time for the three MidPhaseModes,
// queried per step with each ellipsoid's swept bounding sphere or the swept ellipsoid itself, every
// step or looking ahead as World does; the tree build per collider (time, bytes a triangle); and
// how well each split rule copes with the road's thin triangles (filtered / reported per query).
//
//   cmake --build --preset release -j2 --target bench_midphase
//   build/release/bench/bench_midphase
#include <algorithm>
#include <chrono>
#include <cstddef>
#include <memory>
#include <random>
#include <vector>

#include <benchmark/benchmark.h>

#include "midphase_scene.hpp"

namespace {

using namespace trackphys;
using namespace trackphys::bench;

/// The tree variants compared: the write-up's rule, cost-based splits, and cost-based
/// splits with slabs (PlaneTreeSettings::precomputed(), the default).
PlaneTreeSettings variant_settings(std::int64_t variant) {
    PlaneTreeSettings settings = PlaneTreeSettings::precomputed();
    if (variant == 0) settings = PlaneTreeSettings::per_update();
    if (variant == 1) settings.slab_thickness = 0.0;
    return settings;
}

const char* variant_name(std::int64_t variant) {
    return variant == 0 ? "pca_median" : variant == 1 ? "cost_based" : "cost_based+slabs";
}

void BM_MidPhaseUpdate(benchmark::State& state) {
    const MidVariant& variant = mid_variants()[std::size_t(state.range(0))];
    const SubstepCull cull = state.range(1) != 0 ? SubstepCull::bounding_sphere : SubstepCull::none;
    auto mid = make_mid_phase(variant.mode);
    UpdateLists lists;
    std::size_t total = 0, kept = 0;
    for (auto _ : state) {
        total = run_update(*mid, variant, cull, lists, kept);
        benchmark::DoNotOptimize(kept);
    }
    mid->reset_counters();
    total = run_update(*mid, variant, cull, lists, kept);
    const MidPhaseCounters& c = mid->counters();
    state.SetLabel(std::string(variant.name) + (cull == SubstepCull::none ? "" : " +cull"));
    state.counters["tested_per_ell_sub"] = tested_per_ellipsoid_substep(total);
    state.counters["queries"] = double(c.queries);
    state.counters["broad_candidates"] = double(c.broad_phase_candidates);
    state.counters["planes_per_query"] = double(c.planes_tested) / double(c.queries);
    state.counters["filtered_per_query"] = double(c.triangles_filtered) / double(c.queries);
}

/// Every variant side by side in one run: min over repeats of begin_update alone (the
/// per-update stage), of the whole update's mid phase (begin_update + the step lists), and
/// of that plus the sub-step cull; the candidates per ellipsoid per sub-step; and the
/// write-up's loop over ours (World's default), the ratio.
void BM_ModeRatios(benchmark::State& state) {
    const std::vector<MidVariant>& variants = mid_variants();
    const std::size_t n = variants.size();
    std::vector<double> begin_us(n), mid_us(n), cull_us(n), tested(n);
    UpdateLists lists;
    std::size_t kept = 0;
    const auto best_of = [](auto&& run) {
        double best = 1e300;
        for (int repeat = 0; repeat < 200; ++repeat) {
            const auto t0 = std::chrono::steady_clock::now();
            run();
            best = std::min(best, std::chrono::duration<double, std::micro>(
                                      std::chrono::steady_clock::now() - t0)
                                      .count());
        }
        return best;
    };
    for (auto _ : state) {
        for (std::size_t v = 0; v < n; ++v) {
            auto mid = make_mid_phase(variants[v].mode);
            begin_us[v] =
                best_of([&] { mid->begin_update(bench::tightest_turn_scene().update_box); });
            std::size_t total = 0;
            mid_us[v] = best_of(
                [&] { total = run_update(*mid, variants[v], SubstepCull::none, lists, kept); });
            cull_us[v] = best_of([&] {
                total = run_update(*mid, variants[v], SubstepCull::bounding_sphere, lists, kept);
            });
            tested[v] = tested_per_ellipsoid_substep(total);
        }
        benchmark::DoNotOptimize(kept);
    }
    for (std::size_t v = 0; v < n; ++v) {
        const std::string key = std::string("v").append(std::to_string(v)).append("_");
        state.counters[key + "tested"] = tested[v];
        state.counters[key + "begin_us"] = begin_us[v];
        state.counters[key + "mid_us"] = mid_us[v];
        state.counters[key + "cull_us"] = cull_us[v];
    }
    state.counters["writeup/ours_begin"] = begin_us[kWriteupVariant] / begin_us[kDefaultVariant];
    state.counters["writeup/ours_mid"] = mid_us[kWriteupVariant] / mid_us[kDefaultVariant];
    state.counters["writeup/ours_mid+cull"] = cull_us[kWriteupVariant] / cull_us[kDefaultVariant];
    std::string legend;
    for (std::size_t v = 0; v < n; ++v)
        legend.append("v")
            .append(std::to_string(v))
            .append(" ")
            .append(variants[v].name)
            .append("; ");
    state.SetLabel(legend);
}

/// The turn's collider's tree in each variant: build time, size, depth.
void BM_BuildColliderTree(benchmark::State& state) {
    const MidScene& m = mid_scene();
    const PlaneTreeSettings settings = variant_settings(state.range(0));
    const StaticCollider& collider = m.world.collider(m.turn_collider);
    PlaneTree tree;
    for (auto _ : state) {
        tree = make_collider_plane_tree(collider, settings);
        benchmark::DoNotOptimize(tree.nodes().data());
    }
    const double n = double(tree.triangle_count());
    state.SetLabel(variant_name(state.range(0)));
    state.counters["triangles"] = n;
    state.counters["bytes_per_triangle"] = double(tree.bytes_used()) / n;
    state.counters["nodes"] = double(tree.nodes().size());
    state.counters["depth"] = double(tree.depth());
    state.counters["all_colliders_ms"] = m.trees_build_ms;
    state.counters["all_colliders_bytes_per_tri"] =
        double(m.trees_bytes) / double(bench::tightest_turn_scene().track.triangle_count());
}

/// The write-up's complaint, measured: thin road triangles spanning the width overlap the
/// PCA median cuts, so queries filter many triangles they do not report. Random swept
/// spheres and ellipsoids on the road of the turn's collider (the car's radii and step),
/// per split rule: triangles filtered per reported, and planes tested per query.
void BM_SplitQuality(benchmark::State& state) {
    const MidScene& m = mid_scene();
    const TightestTurnScene& s = bench::tightest_turn_scene();
    const PlaneTreeSettings settings = variant_settings(state.range(0));
    const auto shape = static_cast<Shape>(state.range(1));
    const PlaneTree tree = make_collider_plane_tree(m.world.collider(m.turn_collider), settings);

    // Query placements: the collider's centreline samples, random lateral offset and car
    // ellipsoid, moving one step along the road.
    const TrackChunk& chunk = s.track.chunks[m.turn_collider];
    const std::size_t last = m.turn_collider + 1 < s.track.chunks.size()
                                 ? s.track.chunks[m.turn_collider + 1].first_sample
                                 : s.track.centerline.size();
    std::mt19937_64 rng(5);
    std::uniform_int_distribution<std::size_t> sample(chunk.first_sample, last - 1);
    std::uniform_int_distribution<std::size_t> which(0, s.car.ellipsoids.size() - 1);
    std::uniform_real_distribution<double> lateral(-6.0, 6.0);
    std::vector<StepQuery> queries;
    for (int i = 0; i < 512; ++i) {
        const CenterlineSample& c = s.track.centerline[sample(rng)];
        const std::size_t e = which(rng);
        const CarEllipsoid& ce = s.car.ellipsoids[e];
        const glm::dvec3 start = c.position + c.left * (lateral(rng) + ce.center.x) +
                                 c.up * (s.ride_height + ce.center.y);
        const glm::dvec3 end = start + c.tangent * (TightestTurnScene::kSpeed * 0.001);
        const glm::dquat q = glm::quat_cast(glm::dmat3(c.left, c.up, c.tangent));
        queries.push_back({start, end, s.bounding_radius(e), Ellipsoid(start, q, ce.semi_axes)});
    }
    std::vector<std::uint32_t> out;
    PlaneTreeQueryCounts sum;
    for (auto _ : state) {
        sum = {};
        for (const StepQuery& q : queries) {
            out.clear();
            const PlaneTreeQueryCounts c =
                shape == Shape::sphere
                    ? tree.query_swept_sphere(q.start, q.end, q.radius, out)
                    : tree.query_swept_ellipsoid(q.ellipsoid, q.end, kRotationMargin, out);
            sum.planes_tested += c.planes_tested;
            sum.triangles_filtered += c.triangles_filtered;
            sum.triangles_reported += c.triangles_reported;
        }
        benchmark::DoNotOptimize(out.data());
    }
    const double nq = double(queries.size());
    state.SetLabel(std::string(variant_name(state.range(0))) +
                   (shape == Shape::sphere ? " sphere" : " ellipsoid"));
    state.counters["reported_per_query"] = double(sum.triangles_reported) / nq;
    state.counters["filtered_per_query"] = double(sum.triangles_filtered) / nq;
    state.counters["planes_per_query"] = double(sum.planes_tested) / nq;
    state.counters["ns_per_query"] = benchmark::Counter(
        nq, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

BENCHMARK(BM_ModeRatios)->Iterations(1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_MidPhaseUpdate)
    ->ArgsProduct({benchmark::CreateDenseRange(0, int(mid_variants().size()) - 1, 1), {0, 1}})
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_BuildColliderTree)->DenseRange(0, 2)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SplitQuality)->ArgsProduct({{0, 1, 2}, {0, 1}})->Unit(benchmark::kMicrosecond);

}  // namespace
