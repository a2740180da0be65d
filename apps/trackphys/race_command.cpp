#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "commands.hpp"
#include "drive_recording.hpp"
#include "drive_scene.hpp"
#include "drive_svg.hpp"
#include "file_clashes.hpp"
#include "interrupt_guard.hpp"
#include "json_file.hpp"
#include "progress_bar.hpp"
#include "race_report.hpp"
#include "reset_streak.hpp"
#include "staged_outputs.hpp"
#include "tool_world_settings.hpp"
#include "trackphys/error.hpp"
#include "trackphys/io/recording.hpp"
#include "trackphys/io/scenario.hpp"
#include "trackphys/profile/trace_recorder.hpp"
#include "trackphys/world/race_drivers.hpp"
#include "trackphys/world/world.hpp"

namespace trackphys::cli {
namespace {

// What a race runs: the scenario file's track seed, car, field, autopilot speed and
// duration (or the defaults: 20 default cars), with every option given on the command line
// over it.
struct Race {
    Scenario scenario;
    RaceSettings settings;
};

Race build_race(const RaceOptions& o, const OptionGiven& given) {
    Race race;
    Scenario& s = race.scenario;
    if (!o.scenario_file.empty()) {
        s = load_scenario(o.scenario_file);
        if (s.free_mode() || !s.mesh.empty() || !s.map.empty())
            throw Error("scenario '" + o.scenario_file.string() +
                        "': a race runs on a generated track (track.seed), from its grid");
    }
    if (o.scenario_file.empty() || given("--cars")) s.cars = static_cast<int>(o.cars);
    if (given("--seed") && !o.map.empty())
        throw Error("--seed picks a generated track, but this race is on the map '" +
                    o.map.string() + "'");
    if (given("--seed")) s.seed = o.seed;
    if (given("--surface-grips")) s.surfaces = surfaces_of(o.surface_grips);
    check_duration_options(given, o.laps, o.seconds);
    if (given("--laps")) s.laps = o.laps;
    if (given("--seconds")) s.seconds = o.seconds;
    // The field's speeds as the default race's (420 to 600 km/h) for a target of 600.
    race.settings.fastest_kmh = s.target_speed_kmh;
    race.settings.slowest_kmh = 0.7 * s.target_speed_kmh;
    return race;
}

// The option that sets each Scenario field race reads, to name it in validate()'s messages.
constexpr std::pair<const char*, const char*> kRaceFieldOptions[] = {
    {"Scenario.cars", "--cars"},
    {"Scenario.surfaces", "--surface-grips"},
    {"Scenario.laps", "--laps"},
    {"Scenario.seconds", "--seconds"},
};

void check(const RaceOptions& o, const OptionGiven& given) {
    if (o.cars < 1 || o.cars > static_cast<std::size_t>(max_scenario_cars))
        throw Error("--cars must be in [1, " + std::to_string(max_scenario_cars) + "], got " +
                    std::to_string(o.cars));
    check_threads(o.threads);
    if (!o.trace.empty() && given("--threads") && o.threads != 1)
        throw Error(
            "--trace runs the updates on one thread (a trace records only the calling "
            "thread): leave out --threads " +
            std::to_string(o.threads) + " or give --threads 1");
}

// The classification: most laps first, then furthest along the track.
std::vector<RaceCarResult> classify(const RaceDrivers& drivers, const World& world) {
    std::vector<RaceCarResult> results;
    for (std::size_t i = 0; i < drivers.car_count(); ++i)
        results.push_back({i, drivers.target_speed(i) * 3.6, drivers.grip_use(i), drivers.laps(i),
                           drivers.autopilot(i).distance_along(), drivers.lap_times(i),
                           world.car_resets(i) + drivers.rescues(i), drivers.rescues(i)});
    std::stable_sort(
        results.begin(), results.end(),
        [](const RaceCarResult& a, const RaceCarResult& b) { return a.distance_m > b.distance_m; });
    return results;
}

}  // namespace

void run_race(const RaceOptions& o, const OptionGiven& given) {
    check(o, given);
    const Race race = build_race(o, given);
    const Scenario& s = race.scenario;
    if (std::string why = s.validate(); !why.empty())
        fail_scenario(why, kRaceFieldOptions, given, o.scenario_file);
    const auto cars = static_cast<std::size_t>(s.cars);
    refuse_file_clashes({{"--scenario", o.scenario_file}, {"--map", o.map}},
                        {{"--json", o.json},
                         {"--trace", o.trace},
                         {"--record", o.record},
                         {"--record's track mesh",
                          o.record.empty() ? o.record : recording_track_mesh_file(o.record)},
                         {"--svg", o.svg}});
    // As drive: outputs staged first and put in place only after the race succeeded.
    const InterruptGuard interrupt_guard;
    StagedOutputs outputs;
    const auto stage = [&](const std::filesystem::path& path, const char* option) {
        return path.empty() ? path : outputs.stage(path, option);
    };
    const std::filesystem::path json = stage(o.json, "--json"),
                                trace_file = stage(o.trace, "--trace"),
                                record = stage(o.record, "--record"), svg = stage(o.svg, "--svg");

    const DriveScene scene = o.map.empty() ? make_track_scene(s.seed) : make_map_scene(o.map);
    if (!scene.track)
        throw Error("the map '" + o.map.string() +
                    "' was baked from a mesh and has no centreline for the grid and the "
                    "autopilots: race on a map baked from a track (bake --seed)");
    WorldSettings settings = tool_world_settings();
    // The trace records the calling thread's zones only: a full profile needs one thread.
    settings.threads = o.trace.empty() ? o.threads : 1;
    settings.surfaces = surface_table(scene, s.surfaces);
    World world(scene.statics, settings, scene.plane_trees);
    const CarSpec& car = s.car;
    RaceDrivers drivers(*scene.track, car, cars, race.settings);
    drivers.add_cars(world);
    ResetStreak reset_streak(world);
    std::vector<std::uint64_t> rescues(cars);

    const int laps = s.laps == 0 && s.seconds == 0.0 ? 1 : s.laps;
    const double seconds = s.seconds > 0.0 ? s.seconds : laps * kMaxSecondsPerLap;
    std::unique_ptr<TraceRecorder> trace;
    if (!trace_file.empty()) {
        trace = std::make_unique<TraceRecorder>();
        world.set_trace(trace.get());
    }
    std::unique_ptr<RecordingWriter> recording;
    DriveRecordingPlan recording_plan;
    std::vector<std::optional<int>> laps_done(cars);
    if (!record.empty()) {
        recording_plan = plan_drive_recording(o.record, scene, car, settings.dt_update, cars);
        check_destination(recording_plan.track_mesh_file, "--record's track mesh");
        recording = std::make_unique<RecordingWriter>(record, recording_plan.header);
    }

    DrivePlot plot;
    plot.command = "race";
    plot.dt = settings.dt_update;
    if (!svg.empty()) plot.paths.resize(cars);

    RaceReport report;
    report.scene = scene.description + describe_grips(s.surfaces);
    report.cars = cars;
    report.threads = settings.thread_count();
    ProgressBar progress(laps > 0 ? static_cast<double>(laps) : seconds);
    const auto wall_start = std::chrono::steady_clock::now();
    while (world.time() < seconds - 1e-9 && (laps == 0 || drivers.fewest_laps() < laps)) {
        InterruptGuard::check();
        drivers.drive(world);
        world.update();
        drivers.after_update(world);
        for (std::size_t i = 0; i < cars; ++i) rescues[i] = drivers.rescues(i);
        reset_streak.after_update(world, rescues);
        const UpdateProfile& profile = world.last_profile();
        report.profile.add(profile);
        report.car_contacts += profile.car_contacts;
        report.max_car_penetration_m =
            std::max(report.max_car_penetration_m, profile.max_car_penetration);
        const ContactEvents events = world.contact_events();
        report.car_touches += events.car_touch_begins.size();
        report.body_hits += events.body_hits.size();
        if (!svg.empty()) {
            for (std::size_t i = 0; i < cars; ++i) {
                plot.paths[i].points.push_back(world.car(i).state().position);
                plot.paths[i].speed_kmh.push_back(world.car(i).speed() * 3.6);
            }
            plot.update_us.push_back(profile.update_us);
        }
        if (recording) {
            for (std::size_t i = 0; i < cars; ++i) laps_done[i] = drivers.laps(i);
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
    for (const RaceCarResult& c : report.classification) {
        report.resets += c.resets;
        report.rescues += c.rescues;
    }
    report.state_hash = world.state_hash();

    print_race_report(report);
    if (laps > 0 && report.laps_completed < laps)
        throw Error("the last car completed " + std::to_string(report.laps_completed) + " of " +
                    std::to_string(laps) + (laps == 1 ? " lap" : " laps") + " in " +
                    shown(seconds) + " simulated seconds");
    if (!json.empty()) write_race_json(report, json);
    if (!svg.empty()) write_drive_svg(plot, scene.track, svg);
    if (trace) {
        write_trace_file(*trace, trace_file, o.trace);
        std::printf("trace        %s, the updates run on one thread\n", o.trace.string().c_str());
    }
    if (recording) recording->finish();
    commit_with_track_mesh(outputs, recording_plan, scene);
}

}  // namespace trackphys::cli
