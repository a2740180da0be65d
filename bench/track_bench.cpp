// Track generation cost: the default 5 km track (what `trackphys track` and the demo build
// at start-up), and the brute-force update-box count its summary prints.
#include <benchmark/benchmark.h>

#include "trackphys/track/track.hpp"
#include "trackphys/track/track_stats.hpp"

namespace {

void BM_GenerateDefaultTrack(benchmark::State& state) {
    trackphys::TrackParams params;
    params.seed = trackphys::kDemoTrackSeed;
    std::size_t triangles = 0;
    for (auto _ : state) {
        const trackphys::Track track = trackphys::generate_track(params);
        triangles = track.triangle_count();
        benchmark::DoNotOptimize(triangles);
    }
    state.counters["triangles"] = static_cast<double>(triangles);
}
BENCHMARK(BM_GenerateDefaultTrack)
    ->Unit(benchmark::kMillisecond)
    ->Repetitions(5)
    ->ReportAggregatesOnly(true);

void BM_UpdateBoxCountTightestTurn(benchmark::State& state) {
    trackphys::TrackParams params;
    params.seed = trackphys::kDemoTrackSeed;
    const trackphys::Track track = trackphys::generate_track(params);
    const trackphys::TrackStats stats = trackphys::compute_track_stats(track);
    const trackphys::Aabb box = trackphys::car_update_box(track.centerline[stats.tightest_sample]);
    trackphys::BoxTriangleCount count;
    for (auto _ : state) {
        count = trackphys::count_triangles_in_box(track, box);
        benchmark::DoNotOptimize(count);
    }
    state.counters["road_in_box"] = static_cast<double>(count.road);
    state.counters["wall_in_box"] = static_cast<double>(count.wall);
}
BENCHMARK(BM_UpdateBoxCountTightestTurn)->Unit(benchmark::kMicrosecond);

}  // namespace
