// The race group: a field of cars on the default track (RaceDrivers, as `trackphys race`),
// 1 to 128 cars on 1 and 2 threads, and issue 16's targets.

#include <chrono>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "bench_suite.hpp"
#include "drive_scene.hpp"
#include "trackphys/collision/mid_phase.hpp"
#include "trackphys/world/race_drivers.hpp"
#include "trackphys/world/world.hpp"

namespace trackphys::suite {
namespace {

struct RaceTiming {
    Spread update_ns;
    double mean_ns = 0.0;
};

// The race of `cars` cars from the grid: `warm_up` untimed updates (the field spreads out
// and every buffer reaches its size), then `updates` timed ones, wall clock per update.
RaceTiming time_race(const cli::DriveScene& scene, const ColliderPlaneTrees& trees,
                     std::size_t cars, int threads, int warm_up, int updates) {
    WorldSettings settings;
    settings.threads = threads;
    settings.profile = false;
    World world(scene.statics, settings, trees);
    RaceDrivers drivers(*scene.track, CarSpec::default_car(), cars);
    drivers.add_cars(world);
    std::vector<double> ns;
    ns.reserve(static_cast<std::size_t>(updates));
    for (int u = 0; u < warm_up + updates; ++u) {
        drivers.drive(world);
        const auto start = std::chrono::steady_clock::now();
        world.update();
        const auto end = std::chrono::steady_clock::now();
        drivers.after_update(world);
        if (u >= warm_up)
            ns.push_back(std::chrono::duration<double, std::nano>(end - start).count());
    }
    RaceTiming timing;
    for (const double t : ns) timing.mean_ns += t / static_cast<double>(ns.size());
    timing.update_ns = spread(std::move(ns));
    return timing;
}

}  // namespace

void bench_race(BenchRun& run) {
    run.progress("race", "default track");
    const cli::DriveScene scene = cli::make_track_scene(7);
    const ColliderPlaneTrees trees = make_collider_plane_trees(*scene.statics);
    const int warm_up = run.quick() ? 100 : 300;
    const int updates = run.quick() ? 200 : 1000;
    double per_car_worst_us = 0.0;
    double p99_64_on_2_us = 0.0;
    double median_64[3] = {};
    for (const std::size_t cars : {1, 8, 20, 64, 128}) {
        for (const int threads : {1, 2}) {
            const std::string name = std::to_string(cars) + " cars, " + std::to_string(threads) +
                                     " thread" + (threads > 1 ? "s" : "");
            run.progress("race", name);
            const RaceTiming t = time_race(scene, trees, cars, threads, warm_up, updates);
            const std::string versus =
                threads == 1 ? std::string() : std::to_string(cars) + " cars, 1 thread";
            BenchRow& row = run.add("race", name, t.update_ns.median, versus);
            const double per_car_us = t.mean_ns * 1e-3 / static_cast<double>(cars);
            row.figures = {{"p50_us", t.update_ns.median * 1e-3},
                           {"p99_us", t.update_ns.p99 * 1e-3},
                           {"max_us", t.update_ns.max * 1e-3},
                           {"per_car_us", per_car_us},
                           {"updates", double(updates)}};
            row.note = "wall clock per update, after " + std::to_string(warm_up) + " updates";
            if (threads == 1) per_car_worst_us = std::max(per_car_worst_us, per_car_us);
            if (cars == 64) median_64[threads] = t.update_ns.median;
            if (cars == 64 && threads == 2) p99_64_on_2_us = t.update_ns.p99 * 1e-3;
        }
    }
    // Targets as "larger is better" ratios.
    char evidence[128];
    std::snprintf(evidence, sizeof evidence, "p99 %.0f us", p99_64_on_2_us);
    run.add_target("race: 64 cars on 2 threads, 2 ms / update p99", 2000.0 / p99_64_on_2_us, 1.0,
                   true, evidence);
    std::snprintf(evidence, sizeof evidence, "median %.0f us vs %.0f us", median_64[1] * 1e-3,
                  median_64[2] * 1e-3);
    run.add_target("race: 64 cars, 2 threads vs 1 (same run)", median_64[1] / median_64[2], 1.8,
                   true, evidence);
    std::snprintf(evidence, sizeof evidence, "worst %.1f us per car-update", per_car_worst_us);
    run.add_target("race: 50 us per car-update on 1 thread, any field", 50.0 / per_car_worst_us,
                   1.0, true, evidence);
}

}  // namespace trackphys::suite
