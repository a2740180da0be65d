// The vehicle model's cost (issue 20): the gt and formula presets against the arcade car on
// the default track, each driven by its autopilot in the same run, by blocks in turn; the
// thread's CPU time per update, whose mean the target reads. The cars take other lines at
// other speeds, so the collision work differs a little too (the exact tests per update
// are in the figures).

#include <memory>
#include <numeric>
#include <string>
#include <vector>

#include "bench_suite.hpp"
#include "drive_scene.hpp"
#include "tool_world_settings.hpp"
#include "trackphys/world/world.hpp"

namespace trackphys::suite {

void bench_vehicle(BenchRun& run) {
    run.progress("vehicle", "default track");
    const cli::DriveScene scene = cli::make_track_scene(kDemoTrackSeed);
    const int updates = run.quick() ? 300 : 2000;
    const char* presets[] = {"arcade", "gt", "formula"};

    std::vector<std::unique_ptr<World>> worlds;
    std::vector<Driver> drivers;
    std::vector<double> exact_tests(std::size(presets), 0.0);
    for (std::size_t i = 0; i < std::size(presets); ++i) {
        const CarSpec spec = CarSpec::preset(presets[i]);
        ColliderPlaneTrees trees;
        if (!worlds.empty()) trees = worlds.front()->plane_trees();
        worlds.push_back(std::make_unique<World>(scene.statics, cli::tool_world_settings(), trees));
        World& world = *worlds.back();
        world.add_car(spec, cli::start_on_track(*scene.track, spec));
        drivers.push_back({&world.car(0), [&world, &exact_tests, i] {
                               world.update();
                               exact_tests[i] += double(world.last_profile().exact_tests);
                           }});
    }
    run.progress("vehicle", "driving " + std::to_string(updates) + " updates with each preset");
    const std::vector<TimedDrive> drives = drive_timed(*scene.track, drivers, updates);

    const auto mean = [](const std::vector<double>& x) {
        return std::accumulate(x.begin(), x.end(), 0.0) / double(x.size());
    };
    const double arcade_us = mean(drives[0].update_ns) * 1e-3;
    for (std::size_t i = 0; i < drives.size(); ++i) {
        const double added_us = mean(drives[i].update_ns) * 1e-3 - arcade_us;
        BenchRow& row = run.add("vehicle", presets[i], spread(drives[i].update_ns).median,
                                i == 0 ? "" : "arcade");
        row.figures = {{"mean_us", mean(drives[i].update_ns) * 1e-3},
                       {"added_mean_us", added_us},
                       {"exact_tests_per_update", exact_tests[i] / updates},
                       {"final_kmh", drives[i].final_speed_kmh}};
        if (i == 0) continue;
        // The target reads budget / added cost >= 1 (a ratio, larger is better).
        constexpr double kBudgetUs = 5.0;
        run.add_target(std::string(presets[i]) + ": 5 us / vehicle model's added mean per update",
                       kBudgetUs / std::max(added_us, 1e-3), 1.0, true,
                       "added " + std::to_string(added_us) + " us per update");
    }
}

}  // namespace trackphys::suite
