// The vehicle model's cost (issue 20): the gt and formula presets against the arcade car on
// the default track, each driven by its autopilot in the same run, by blocks in turn; the
// thread's CPU time per update. The cars take other lines at other speeds, so the collision
// phases differ by the line as well as the model: the target reads the integrate phase
// (World::advance: the car's forces and integration, where all of the model's code runs),
// and the whole update's difference is a figure beside it.

#include <cstdio>
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
    std::vector<double> integrate_us(std::size(presets), 0.0);
    std::vector<double> collision_us(std::size(presets), 0.0);  // every other phase
    for (std::size_t i = 0; i < std::size(presets); ++i) {
        const CarSpec spec = CarSpec::preset(presets[i]);
        ColliderPlaneTrees trees;
        if (!worlds.empty()) trees = worlds.front()->plane_trees();
        worlds.push_back(std::make_unique<World>(scene.statics, cli::tool_world_settings(), trees));
        World& world = *worlds.back();
        world.add_car(spec, cli::start_on_track(*scene.track, spec));
        drivers.push_back({&world.car(0), [&world, &exact_tests, &integrate_us, &collision_us, i] {
                               world.update();
                               const UpdateProfile& profile = world.last_profile();
                               exact_tests[i] += double(profile.exact_tests);
                               integrate_us[i] += profile[Phase::integrate];
                               collision_us[i] += profile[Phase::broad] + profile[Phase::mid] +
                                                  profile[Phase::cull] + profile[Phase::exact];
                           }});
    }
    run.progress("vehicle", "driving " + std::to_string(updates) + " updates with each preset");
    const std::vector<TimedDrive> drives = drive_timed(*scene.track, drivers, updates);

    const auto mean = [](const std::vector<double>& x) {
        return std::accumulate(x.begin(), x.end(), 0.0) / double(x.size());
    };
    const double arcade_us = mean(drives[0].update_ns) * 1e-3;
    const double arcade_integrate_us = integrate_us[0] / updates;
    for (std::size_t i = 0; i < drives.size(); ++i) {
        const double added_us = mean(drives[i].update_ns) * 1e-3 - arcade_us;
        const double added_integrate_us = integrate_us[i] / updates - arcade_integrate_us;
        const double added_collision_us = (collision_us[i] - collision_us[0]) / updates;
        BenchRow& row = run.add("vehicle", presets[i], spread(drives[i].update_ns).median,
                                i == 0 ? "" : "arcade");
        row.figures = {{"mean_us", mean(drives[i].update_ns) * 1e-3},
                       {"added_mean_us", added_us},
                       {"integrate_us", integrate_us[i] / updates},
                       {"added_integrate_us", added_integrate_us},
                       {"added_collision_us", added_collision_us},
                       {"exact_tests_per_update", exact_tests[i] / updates},
                       {"final_kmh", drives[i].final_speed_kmh},
                       {"resets", double(worlds[i]->car_resets(0))}};
        if (i == 0) continue;
        // The target reads budget / added cost >= 1 (a ratio, larger is better), on a drive
        // without resets (a reset car skips the work it would have done) and with the phases
        // timed (without the profile every phase reads 0).
        constexpr double kBudgetUs = 5.0;
        char evidence[160];
        std::snprintf(evidence, sizeof evidence,
                      "integrate phase %+.2f us; whole update %+.2f us, the collision phases "
                      "along its own line %+.2f us; resets %llu",
                      added_integrate_us, added_us, added_collision_us,
                      static_cast<unsigned long long>(worlds[i]->car_resets(0)));
        run.add_target(std::string(presets[i]) +
                           ": 5 us / vehicle model's added cost per update (integrate phase)",
                       kBudgetUs / std::max(added_integrate_us, 1e-3), 1.0,
                       worlds[0]->car_resets(0) == 0 && worlds[i]->car_resets(0) == 0 &&
                           integrate_us[0] > 0.0 && integrate_us[i] > 0.0,
                       evidence);
    }
}

}  // namespace trackphys::suite
