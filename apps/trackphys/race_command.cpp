#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "commands.hpp"
#include "drive_recording.hpp"
#include "drive_scene.hpp"
#include "drive_svg.hpp"
#include "interrupt_guard.hpp"
#include "json_file.hpp"
#include "progress_bar.hpp"
#include "race_report.hpp"
#include "staged_outputs.hpp"
#include "trackphys/error.hpp"
#include "trackphys/io/recording.hpp"
#include "trackphys/profile/trace_recorder.hpp"
#include "trackphys/world/race_drivers.hpp"
#include "trackphys/world/world.hpp"

namespace trackphys::cli {
namespace {

struct RaceOptions {
    std::uint64_t seed = 7;
    std::size_t cars = 20;
    int laps = 0;
    double seconds = 0.0;
    int threads = 0;
    std::filesystem::path json, trace, record, svg;
};

constexpr std::size_t kMaxCars = 128;
// A lap that takes longer than this (simulated) means a car is stuck: give up (as drive).
constexpr double kMaxSecondsPerLap = 600.0;

void check(const RaceOptions& o) {
    if (o.cars < 1 || o.cars > kMaxCars)
        throw Error("--cars must be in [1, " + std::to_string(kMaxCars) + "], got " +
                    std::to_string(o.cars));
    if (o.laps < 0) throw Error("--laps must be >= 0, got " + std::to_string(o.laps));
    if (!(o.seconds >= 0.0 && o.seconds < 1e7))
        throw Error("--seconds must be finite and >= 0, got " + std::to_string(o.seconds));
    if (o.threads < 0 || o.threads > 256)
        throw Error("--threads must be in [0, 256] (0: the hardware's count), got " +
                    std::to_string(o.threads));
}

// The classification: most laps first, then furthest along the track.
std::vector<RaceCarResult> classify(const RaceDrivers& drivers, const World& world) {
    std::vector<RaceCarResult> results;
    for (std::size_t i = 0; i < drivers.car_count(); ++i)
        results.push_back({i, drivers.target_speed(i) * 3.6, drivers.laps(i),
                           drivers.autopilot(i).distance_along(), drivers.lap_times(i),
                           world.car_resets(i)});
    std::stable_sort(
        results.begin(), results.end(),
        [](const RaceCarResult& a, const RaceCarResult& b) { return a.distance_m > b.distance_m; });
    return results;
}

void run(const RaceOptions& o) {
    check(o);
    // As drive: outputs staged first and put in place only after the race succeeded.
    const InterruptGuard interrupt_guard;
    StagedOutputs outputs;
    const auto stage = [&](const std::filesystem::path& path, const char* option) {
        return path.empty() ? path : outputs.stage(path, option);
    };
    const std::filesystem::path json = stage(o.json, "--json"),
                                trace_file = stage(o.trace, "--trace"),
                                record = stage(o.record, "--record"), svg = stage(o.svg, "--svg");

    const DriveScene scene = make_track_scene(o.seed);
    WorldSettings settings;
    settings.threads = o.threads;
    World world(scene.statics, settings);
    const CarSpec car = CarSpec::default_car();
    RaceDrivers drivers(*scene.track, car, o.cars);
    drivers.add_cars(world);

    const int laps = o.laps == 0 && o.seconds == 0.0 ? 1 : o.laps;
    const double seconds = o.seconds > 0.0 ? o.seconds : laps * kMaxSecondsPerLap;
    std::unique_ptr<TraceRecorder> trace;
    if (!trace_file.empty()) {
        trace = std::make_unique<TraceRecorder>();
        world.set_trace(trace.get());
    }
    std::unique_ptr<RecordingWriter> recording;
    DriveRecordingPlan recording_plan;
    std::vector<std::optional<int>> laps_done(o.cars);
    if (!record.empty()) {
        recording_plan = plan_drive_recording(o.record, scene, {}, car, settings.dt_update, o.cars);
        check_destination(recording_plan.track_mesh_file, "--record's track mesh");
        recording = std::make_unique<RecordingWriter>(record, recording_plan.header);
    }

    DrivePlot plot;
    plot.command = "race";
    plot.dt = settings.dt_update;
    if (!svg.empty()) plot.paths.resize(o.cars);

    RaceReport report;
    report.scene = scene.description;
    report.cars = o.cars;
    report.threads = settings.thread_count();
    ProgressBar progress(laps > 0 ? static_cast<double>(laps) : seconds);
    const auto wall_start = std::chrono::steady_clock::now();
    while (world.time() < seconds - 1e-9 && (laps == 0 || drivers.fewest_laps() < laps)) {
        InterruptGuard::check();
        drivers.drive(world);
        world.update();
        drivers.after_update(world);
        const UpdateProfile& profile = world.last_profile();
        report.profile.add(profile);
        report.car_contacts += profile.car_contacts;
        report.max_car_penetration_m =
            std::max(report.max_car_penetration_m, profile.max_car_penetration);
        if (!svg.empty()) {
            for (std::size_t i = 0; i < o.cars; ++i) {
                plot.paths[i].points.push_back(world.car(i).state().position);
                plot.paths[i].speed_kmh.push_back(world.car(i).speed() * 3.6);
            }
            plot.update_us.push_back(profile.update_us);
        }
        if (recording) {
            for (std::size_t i = 0; i < o.cars; ++i) laps_done[i] = drivers.laps(i);
            recording->write_frame(world, laps_done);
        }
        // Laps of the last car (or time), beside the pole car's speed.
        progress.show(laps > 0 ? static_cast<double>(drivers.fewest_laps()) : world.time(),
                      world.car(0).speed() * 3.6);
    }
    report.wall_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
    report.updates = world.update_count();
    report.simulated_s = world.time();
    report.laps_completed = drivers.fewest_laps();
    report.classification = classify(drivers, world);
    for (std::size_t i = 0; i < o.cars; ++i) report.resets += world.car_resets(i);
    report.state_hash = world.state_hash();

    print_race_report(report);
    if (laps > 0 && report.laps_completed < laps)
        throw Error("the last car completed " + std::to_string(report.laps_completed) + " of " +
                    std::to_string(laps) + " laps in " + std::to_string(seconds) +
                    " simulated seconds");
    if (!json.empty()) write_race_json(report, json);
    if (!svg.empty()) write_drive_svg(plot, scene.track, svg);
    if (trace) write_trace_file(*trace, trace_file, o.trace);
    if (recording) recording->finish();
    commit_with_track_mesh(outputs, recording_plan, scene);
}

}  // namespace

void add_race_command(CLI::App& app) {
    auto o = std::make_shared<RaceOptions>();
    CLI::App* command = app.add_subcommand(
        "race",
        "Race a field of default cars on a generated track: a two-column grid, each car on its "
        "own autopilot and target speed, passing slower cars on the side; the cars collide. "
        "Prints the classification and the per-update profile of the whole world");
    command->add_option("--seed", o->seed, "Seed of the generated track")
        ->check(not_negative())
        ->capture_default_str();
    command->add_option("--cars", o->cars, "Cars on the grid (1 to 128)")
        ->check(not_negative())
        ->capture_default_str();
    command->add_option("--laps", o->laps,
                        "Laps every car must complete (default 1 without --seconds)");
    command->add_option("--seconds", o->seconds, "Simulated seconds to race");
    command
        ->add_option("--threads", o->threads,
                     "Threads to update the world on (0: the hardware's count)")
        ->capture_default_str();
    command->add_option("--json", o->json, "Write the figures as JSON");
    command->add_option("--trace", o->trace,
                        "Write a Chrome trace (Perfetto) of the updates run on one thread");
    command->add_option("--svg", o->svg,
                        "Plot every car's path over the track and the update times");
    command->add_option("--record", o->record,
                        "Write every car's pose and contacts per update (JSON Lines) for a viewer");
    command->callback([o] { run(*o); });
}

}  // namespace trackphys::cli
