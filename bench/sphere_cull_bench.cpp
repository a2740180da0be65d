// The write-up's cull improvements, measured on the same inputs (cull_scene.hpp): the
// broad-phase candidates of the default track's tightest banked turn (a car's update box
// padded for 1000 km/h) against the bounding spheres of the default car's 8 ellipsoids over
// the 40 sub-steps of one update driving through it.
//   1. origin at the first vertex, tests in x, y, z order (its first version)
//   2. the same layout, normal test first ("about half the cull time")
//   3. longest-edge origin, normal first, no min/max ("a little more")
// trackphys-bench runs the same passes (its "cull" group).
#include <benchmark/benchmark.h>

#include "cull_scene.hpp"

namespace {

using trackphys::bench::CullScene;
using trackphys::bench::CullVariant;

const CullScene& scene() {
    static const CullScene instance(trackphys::bench::tightest_turn_scene());
    return instance;
}

void run_cull(benchmark::State& state, CullVariant variant) {
    std::size_t kept = 0;
    for (auto _ : state) {
        kept = cull_pass(scene(), variant);
        benchmark::DoNotOptimize(kept);
    }
    const double tests = double(scene().tests());
    state.counters["candidates"] = double(scene().longest_edge_origin.size());
    state.counters["kept_%"] = 100.0 * double(kept) / tests;
    state.counters["ns_per_test"] = benchmark::Counter(
        tests, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

void BM_Cull1_ArbitraryOrigin_XYZ(benchmark::State& state) {
    run_cull(state, CullVariant::xyz_order);
}
void BM_Cull2_ArbitraryOrigin_NormalFirst(benchmark::State& state) {
    run_cull(state, CullVariant::normal_first);
}
void BM_Cull3_LongestEdge_NormalFirst(benchmark::State& state) {
    run_cull(state, CullVariant::longest_edge_normal_first);
}

BENCHMARK(BM_Cull1_ArbitraryOrigin_XYZ)
    ->Unit(benchmark::kMicrosecond)
    ->Repetitions(5)
    ->ReportAggregatesOnly(true);
BENCHMARK(BM_Cull2_ArbitraryOrigin_NormalFirst)
    ->Unit(benchmark::kMicrosecond)
    ->Repetitions(5)
    ->ReportAggregatesOnly(true);
BENCHMARK(BM_Cull3_LongestEdge_NormalFirst)
    ->Unit(benchmark::kMicrosecond)
    ->Repetitions(5)
    ->ReportAggregatesOnly(true);

}  // namespace
