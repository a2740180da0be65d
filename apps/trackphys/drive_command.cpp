#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>

#include "commands.hpp"
#include "drive_recording.hpp"
#include "drive_report.hpp"
#include "drive_scene.hpp"
#include "drive_session.hpp"
#include "drive_svg.hpp"
#include "file_clashes.hpp"
#include "interrupt_guard.hpp"
#include "json_file.hpp"
#include "progress_bar.hpp"
#include "reset_streak.hpp"
#include "staged_outputs.hpp"
#include "telemetry_csv.hpp"
#include "tool_world_settings.hpp"
#include "trackphys/error.hpp"
#include "trackphys/io/car_spec_json.hpp"
#include "trackphys/io/recording.hpp"
#include "trackphys/io/scenario.hpp"
#include "trackphys/io/snapshot_file.hpp"
#include "trackphys/profile/trace_recorder.hpp"
#include "trackphys/world/autopilot.hpp"
#include "trackphys/world/world.hpp"
#include "trackphys/world/world_snapshot.hpp"

namespace trackphys::cli {
namespace {

// --save-at T FILE, checked; the snapshot is written to `staged` (staged_outputs.hpp).
struct SavePoint {
    double seconds;
    std::filesystem::path file;
    std::filesystem::path staged;
};

// The option that sets each Scenario field, to name it in Scenario::validate()'s messages.
constexpr std::pair<const char*, const char*> kDriveFieldOptions[] = {
    {"Scenario.mesh", "--mesh"},
    {"Scenario.map", "--map"},
    {"Scenario.spawn", "--spawn"},
    {"Scenario.heading_deg", "--heading"},
    {"Scenario.surfaces", "--surface-grips"},
    {"Scenario.target_speed_kmh", "--target-speed"},
    {"Scenario.inputs.throttle", "--throttle"},
    {"Scenario.inputs.steer", "--steer"},
    {"Scenario.laps", "--laps"},
    {"Scenario.seconds", "--seconds"},
};

// The scenario file (or the defaults) with the car file and every scene option given on
// the command line applied over it: a flag overrides the same field of the file. A flag
// that the resulting mode does not use is an error rather than silently ignored.
Scenario build_scenario(const DriveOptions& o, const OptionGiven& given) {
    Scenario s = o.scenario_file.empty() ? Scenario{} : load_scenario(o.scenario_file);
    if (!o.car_file.empty()) s.car = load_car_spec(o.car_file);
    if (given("--car-preset")) s.car = CarSpec::preset(o.car_preset);
    const Scenario& f = o.flags;
    if (given("--seed")) s.seed = f.seed;
    if (given("--mesh")) s.mesh = f.mesh;
    if (given("--map")) s.map = f.map;
    if (given("--spawn")) s.spawn = glm::dvec3(o.spawn.at(0), o.spawn.at(1), o.spawn.at(2));
    if (given("--heading")) s.heading_deg = f.heading_deg;
    if (given("--surface-grips")) s.surfaces = surfaces_of(o.surface_grips);
    if (given("--target-speed")) s.target_speed_kmh = f.target_speed_kmh;
    if (given("--throttle")) s.inputs.throttle = f.inputs.throttle;
    if (given("--steer")) s.inputs.steer = f.inputs.steer;
    check_duration_options(given, f.laps, f.seconds);
    if (given("--laps")) s.laps = f.laps;
    if (given("--seconds")) s.seconds = f.seconds;

    if (given("--seed") && !s.mesh.empty())
        throw Error("--seed picks a generated track, but this drive is on the mesh '" +
                    s.mesh.string() + "'");
    if (given("--seed") && !s.map.empty())
        throw Error("--seed picks a generated track, but this drive is on the map '" +
                    s.map.string() + "'");
    if (given("--target-speed") && s.free_mode())
        throw Error(
            "--target-speed sets the autopilot, which does not drive in free mode (a spawn point): "
            "use --throttle and --steer");
    for (const char* option : {"--throttle", "--steer", "--heading"})
        if (given(option) && !s.free_mode())
            throw Error(std::string(option) +
                        " applies in free mode only: add --spawn x,y,z (without a spawn "
                        "point the autopilot drives the generated track from its start line)");
    if (s.mesh.empty())
        refuse_unused_mesh_limits(
            given, "drive",
            s.map.empty() ? "a generated track" : "the map '" + s.map.string() + "'");
    if (s.free_mode() && s.seconds == 0.0 && s.laps == 0 && o.scenario_file.empty())
        throw Error(
            "--spawn drives in free mode for --seconds S, which is missing (laps need "
            "the generated track)");
    std::string why = s.validate();
    if (why.empty() && s.cars > 1)
        why = "Scenario.cars is " + std::to_string(s.cars) +
              ": drive drives one car (race a field with trackphys race --scenario)";
    if (why.empty()) return s;
    fail_scenario(why, kDriveFieldOptions, given, o.scenario_file);
}

std::optional<SavePoint> parse_save_at(const DriveOptions& o, double drive_seconds) {
    const auto& [time, file] = o.save_at;
    if (file.empty()) return std::nullopt;
    SavePoint point{0.0, file, {}};
    std::size_t used = 0;
    try {
        point.seconds = std::stod(time, &used);
    } catch (const std::exception&) {
        used = 0;
    }
    if (used != time.size() || !std::isfinite(point.seconds) || point.seconds < 0.0)
        throw Error("--save-at '" + time + "': the time must be a finite number of seconds >= 0");
    if (drive_seconds > 0.0 && point.seconds > drive_seconds + 1e-9)
        throw Error("--save-at " + time + " is after the drive's end (--seconds " +
                    shown(drive_seconds) + ")");
    return point;
}

// A snapshot at or past the drive's end would resume a drive of nothing: a silent success.
void check_resume_before_the_end(const std::filesystem::path& file, double snapshot_seconds,
                                 double end_seconds, const DriveSession& saved, int laps) {
    const std::string name = "--resume '" + file.string() + "': ";
    char text[160];
    if (laps > 0 && saved.lap_times_s.size() >= static_cast<std::size_t>(laps)) {
        const std::size_t done = saved.lap_times_s.size();
        std::snprintf(text, sizeof text,
                      "the snapshot's drive has already completed %zu lap%s, the drive's end "
                      "(--laps %d)",
                      done, done == 1 ? "" : "s", laps);
        throw Error(name + text);
    }
    if (snapshot_seconds >= end_seconds - 1e-9) {
        std::snprintf(text, sizeof text,
                      "the snapshot is at %.2f s, at or after the drive's end (--seconds %g)",
                      snapshot_seconds, end_seconds);
        throw Error(name + text);
    }
}

// Runs step, naming the snapshot in its error: the library's messages do not know the file.
template <class Step>
auto naming_snapshot(const std::filesystem::path& file, Step&& step) {
    try {
        return step();
    } catch (const Error& e) {
        throw Error("--resume '" + file.string() + "': " + e.what());
    }
}

}  // namespace

void run_drive(const DriveOptions& o, const OptionGiven& given) {
    if (o.track != "default")
        throw Error("--track '" + o.track + "': the only generated track is 'default'");
    const Scenario s = build_scenario(o, given);
    if (o.print_car) {
        std::fputs(car_spec_to_json(s.car).c_str(), stdout);
        return;
    }
    if (o.print_scenario) {
        // s's names are as given, relative to the current folder (a --scenario file's
        // relative names joined to its folder): right for a scenario file saved there, which
        // reads them from its own folder.
        std::fputs(scenario_to_json(s).c_str(), stdout);
        return;
    }
    refuse_file_clashes({{"--scenario", o.scenario_file},
                         {"--car", o.car_file},
                         {s.mesh == o.flags.mesh ? "--mesh" : "the scenario's track.mesh", s.mesh},
                         {s.map == o.flags.map ? "--map" : "the scenario's track.map", s.map},
                         {"--resume", o.resume}},
                        {{"--json", o.json},
                         {"--trace", o.trace},
                         {"--record", o.record},
                         {"--record's track mesh",
                          o.record.empty() ? o.record : recording_track_mesh_file(o.record)},
                         {"--svg", o.svg},
                         {"--telemetry", o.telemetry},
                         {"--save-at", o.save_at.second}});
    // Every output is checked and staged before the drive, and put in place only after it
    // succeeded: a failure anywhere, Ctrl-C included, leaves none of them behind (the
    // snapshot of --save-at too).
    const InterruptGuard interrupt_guard;
    StagedOutputs outputs;
    const auto stage = [&](const std::filesystem::path& path, const char* option) {
        return path.empty() ? path : outputs.stage(path, option);
    };
    const std::filesystem::path json = stage(o.json, "--json"),
                                trace_file = stage(o.trace, "--trace"),
                                record = stage(o.record, "--record"), svg = stage(o.svg, "--svg"),
                                telemetry_file = stage(o.telemetry, "--telemetry");
    std::optional<SavePoint> save_at = parse_save_at(o, s.seconds);
    if (save_at) save_at->staged = stage(save_at->file, "--save-at");
    DriveSession session;
    session.free_mode = s.free_mode();
    session.seed = s.seed;
    session.target_speed_kmh = s.target_speed_kmh;
    session.throttle = s.inputs.throttle;
    session.steer = s.inputs.steer;
    for (const Surface& surface : s.surfaces) session.surface_grips.push_back(surface.grip);
    std::optional<SnapshotFile> resume;
    if (!o.resume.empty()) {
        resume = load_snapshot(o.resume);
        const DriveSession saved =
            naming_snapshot(o.resume, [&] { return parse_session(resume->user_data); });
        check_same_drive(saved, session);
        // World::restore_state would refuse it too, but by the spec's fingerprint alone.
        if (resume->world.cars.size() == 1 &&
            resume->world.cars[0].spec_fingerprint != fingerprint(s.car))
            throw Error(
                "--resume: the snapshot was made with another car (--car, --car-preset "
                "or the scenario's car; resume with the original drive's options)");
        session = saved;
    }

    const DriveScene scene = !s.map.empty()    ? make_map_scene(s.map)
                             : !s.mesh.empty() ? make_mesh_scene(s.mesh, o.mesh_limits)
                                               : make_track_scene(s.seed);
    if (!s.free_mode() && !scene.track)
        throw Error("the map '" + s.map.string() +
                    "' was baked from a mesh and has no centreline for the autopilot: give "
                    "--spawn x,y,z to drive it in free mode");
    WorldSettings world_settings = tool_world_settings();
    world_settings.surfaces = surface_table(scene, s.surfaces);
    // World::restore_state would refuse it too, but by collider fingerprints alone.
    if (resume && resume->world.colliders != fingerprint(*scene.statics))
        throw Error(
            "--resume: the snapshot was made on another scene (its static colliders "
            "are not those of " +
            scene.description + "; resume with the original drive's --mesh or --map)");
    World world(scene.statics, world_settings, scene.plane_trees);
    const RigidBodyState start =
        s.free_mode() ? spawn_on_surface(*scene.statics, s.car, *s.spawn, s.heading_deg)
                      : start_on_track(*scene.track, s.car);
    world.add_car(s.car, start);
    // Resuming: the same static world, settings and car (restore_state checks their
    // fingerprints), then the snapshot's state, update count and time.
    if (resume) naming_snapshot(o.resume, [&] { world.restore_state(resume->world); });
    ResetStreak reset_streak(world);

    std::optional<Autopilot> autopilot;
    if (!s.free_mode()) {
        AutopilotSettings settings;
        settings.target_speed = s.target_speed_kmh / 3.6;
        autopilot.emplace(*scene.track, s.car, settings);
        if (session.autopilot) autopilot->set_progress(*session.autopilot);
    }
    const int laps = !s.free_mode() && s.laps == 0 && s.seconds == 0.0 ? 1 : s.laps;
    const double seconds = s.seconds > 0.0 ? s.seconds : laps * kMaxSecondsPerLap;
    if (resume) check_resume_before_the_end(o.resume, world.time(), seconds, session, laps);

    std::unique_ptr<TraceRecorder> trace;
    if (!trace_file.empty()) {
        trace = std::make_unique<TraceRecorder>();
        world.set_trace(trace.get());
    }
    std::unique_ptr<RecordingWriter> recording;
    DriveRecordingPlan recording_plan;
    if (!record.empty()) {
        recording_plan = plan_drive_recording(o.record, scene, s.car, world.settings().dt_update);
        check_destination(recording_plan.track_mesh_file, "--record's track mesh");
        recording = std::make_unique<RecordingWriter>(record, recording_plan.header);
    }

    std::optional<TelemetryCsv> telemetry;
    if (!telemetry_file.empty()) telemetry.emplace(telemetry_file, world.car(0));

    DriveReport report;
    report.scene = scene.description + describe_grips(s.surfaces);
    report.triangles = scene.triangle_count;
    report.distance_m = session.distance_m;
    report.top_speed_kmh = session.top_speed_kmh;
    report.lap_times_s = session.lap_times_s;
    DrivePlot plot;
    plot.dt = world.settings().dt_update;
    PlotPath& car_path = plot.paths.emplace_back();
    ProgressBar progress(laps > 0 ? static_cast<double>(laps) : seconds);
    const auto wall_start = std::chrono::steady_clock::now();
    glm::dvec3 previous = world.car(0).state().position;
    // Saves once, at the first moment the simulated time has reached --save-at's.
    bool saved = false;
    const auto save_if_due = [&] {
        if (!save_at || saved || world.time() < save_at->seconds - 1e-9) return;
        session.autopilot = autopilot ? std::optional(autopilot->progress()) : std::nullopt;
        session.distance_m = report.distance_m;
        session.top_speed_kmh = report.top_speed_kmh;
        session.lap_times_s = report.lap_times_s;
        save_snapshot(save_at->staged, world.save_state(), session_json(session));
        std::printf("snapshot     %s at %.2f s\n", save_at->file.string().c_str(), world.time());
        saved = true;
    };
    save_if_due();

    while (world.time() < seconds - 1e-9 && (laps == 0 || autopilot->laps() < laps)) {
        InterruptGuard::check();
        Car& car = world.car(0);
        car.set_inputs(autopilot ? autopilot->drive(car) : s.inputs);
        const int laps_before = autopilot ? autopilot->laps() : 0;
        world.update();
        reset_streak.after_update(world);
        if (autopilot) {
            autopilot->locate(car);
            if (autopilot->laps() > laps_before) {
                double previous_laps = 0.0;
                for (double t : report.lap_times_s) previous_laps += t;
                report.lap_times_s.push_back(world.time() - previous_laps);
            }
        }
        const RigidBodyState& state = car.state();
        report.distance_m += glm::length(state.position - previous);
        previous = state.position;
        report.top_speed_kmh = std::max(report.top_speed_kmh, car.speed() * 3.6);
        report.profile.add(world.last_profile());
        car_path.points.push_back(state.position);
        car_path.speed_kmh.push_back(car.speed() * 3.6);
        plot.update_us.push_back(world.last_profile().update_us);
        if (recording) {
            const std::optional<int> laps_done =
                autopilot ? std::optional(autopilot->laps()) : std::nullopt;
            recording->write_frame(world, {&laps_done, 1});
        }
        if (telemetry) telemetry->add(world.time(), car);
        progress.show(laps > 0 ? autopilot->laps() +
                                     autopilot->distance_along() / scene.track->length_m -
                                     autopilot->laps()
                               : world.time(),
                      car.speed() * 3.6);
        save_if_due();
    }
    report.wall_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
    report.updates = world.update_count();
    report.simulated_s = world.time();
    report.laps_completed = autopilot ? autopilot->laps() : 0;
    report.final_position = world.car(0).state().position;
    report.state_hash = world.state_hash();
    report.resets = world.car_resets(0);
    report.last_reset = world.last_reset_reason(0);

    print_drive_report(report);
    if (save_at && !saved)
        throw Error("--save-at " + o.save_at.first + ": the drive ended at " + shown(world.time()) +
                    " s, before that time; no snapshot written");
    if (laps > 0 && report.laps_completed < laps)
        throw Error("the car completed " + std::to_string(report.laps_completed) + " of " +
                    std::to_string(laps) + (laps == 1 ? " lap" : " laps") + " in " +
                    shown(seconds) + " simulated seconds");
    if (!json.empty()) write_drive_json(report, json);
    if (!svg.empty()) write_drive_svg(plot, scene.track, svg);
    if (trace) write_trace_file(*trace, trace_file, o.trace);
    if (recording) recording->finish();
    if (telemetry) telemetry->finish();
    commit_with_track_mesh(outputs, recording_plan, scene);
}

}  // namespace trackphys::cli
