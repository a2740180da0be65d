// The write-up's cull improvements, measured on the same inputs: the broad-phase candidates
// of the default track's tightest banked turn (a car's update box padded for 1000 km/h)
// against the bounding spheres of the default car's 8 ellipsoids over the 40 sub-steps of
// one update driving through it.
//   1. origin at the first vertex, tests in x, y, z order (its first version)
//   2. the same layout, normal test first ("about half the cull time")
//   3. longest-edge origin, normal first, no min/max ("a little more")
#include <vector>

#include <benchmark/benchmark.h>
#include <glm/geometric.hpp>

#include "tightest_turn_scene.hpp"
#include "trackphys/geometry/normalized_triangle.hpp"
#include "trackphys/geometry/sphere_cull_variants.hpp"

namespace {

using namespace trackphys;

struct Sphere {
    glm::dvec3 center;
    double radius;
};

struct CullScene {
    std::vector<Triangle> candidates;
    std::vector<Sphere> spheres;  // 40 sub-steps x 8 ellipsoids
};

CullScene make_tightest_turn_scene() {
    const bench::TightestTurnScene& turn = bench::tightest_turn_scene();
    CullScene scene;
    scene.candidates = turn.candidates();
    for (int substep = 0; substep < bench::TightestTurnScene::kSubsteps; ++substep)
        for (std::size_t e = 0; e < turn.car.ellipsoids.size(); ++e)
            scene.spheres.push_back({turn.center(e, substep), turn.bounding_radius(e)});
    return scene;
}

const CullScene& scene() {
    static const CullScene instance = make_tightest_turn_scene();
    return instance;
}

template <class Stored, class Test>
void run_cull(benchmark::State& state, const std::vector<Stored>& stored, Test test) {
    std::size_t kept = 0;
    for (auto _ : state) {
        kept = 0;
        for (const Sphere& s : scene().spheres)
            for (const Stored& t : stored) kept += test(t, s) ? 1 : 0;
        benchmark::DoNotOptimize(kept);
    }
    const double tests = double(scene().spheres.size() * stored.size());
    state.counters["candidates"] = double(stored.size());
    state.counters["kept_%"] = 100.0 * double(kept) / tests;
    state.counters["ns_per_test"] =
        benchmark::Counter(tests, benchmark::Counter::kIsIterationInvariantRate |
                                      benchmark::Counter::kInvert);
}

void BM_Cull1_ArbitraryOrigin_XYZ(benchmark::State& state) {
    std::vector<ArbitraryOriginTriangle> stored(scene().candidates.begin(), scene().candidates.end());
    run_cull(state, stored, [](const ArbitraryOriginTriangle& t, const Sphere& s) {
        return t.may_touch_sphere_xyz(s.center, s.radius);
    });
}

void BM_Cull2_ArbitraryOrigin_NormalFirst(benchmark::State& state) {
    std::vector<ArbitraryOriginTriangle> stored(scene().candidates.begin(), scene().candidates.end());
    run_cull(state, stored, [](const ArbitraryOriginTriangle& t, const Sphere& s) {
        return t.may_touch_sphere_normal_first(s.center, s.radius);
    });
}

void BM_Cull3_LongestEdge_NormalFirst(benchmark::State& state) {
    std::vector<NormalizedTriangle> stored(scene().candidates.begin(), scene().candidates.end());
    run_cull(state, stored, [](const NormalizedTriangle& t, const Sphere& s) {
        return t.may_touch_sphere(s.center, s.radius);
    });
}

BENCHMARK(BM_Cull1_ArbitraryOrigin_XYZ)->Unit(benchmark::kMicrosecond)->Repetitions(5)->ReportAggregatesOnly(true);
BENCHMARK(BM_Cull2_ArbitraryOrigin_NormalFirst)->Unit(benchmark::kMicrosecond)->Repetitions(5)->ReportAggregatesOnly(true);
BENCHMARK(BM_Cull3_LongestEdge_NormalFirst)->Unit(benchmark::kMicrosecond)->Repetitions(5)->ReportAggregatesOnly(true);

}  // namespace
