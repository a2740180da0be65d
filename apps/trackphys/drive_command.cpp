#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <unistd.h>

#include <glm/geometric.hpp>

#include "commands.hpp"
#include "drive_report.hpp"
#include "drive_scene.hpp"
#include "drive_session.hpp"
#include "drive_svg.hpp"
#include "trackphys/error.hpp"
#include "trackphys/io/recording.hpp"
#include "trackphys/io/snapshot_file.hpp"
#include "trackphys/profile/trace_recorder.hpp"
#include "trackphys/world/autopilot.hpp"
#include "trackphys/world/world.hpp"

namespace trackphys::cli {
namespace {

struct DriveOptions {
    std::string track = "default";
    std::uint64_t seed = 7;
    std::filesystem::path mesh;
    int laps = 0;
    double seconds = 0.0;
    double target_speed_kmh = 600.0;
    std::vector<double> spawn;
    double heading_deg = 0.0;
    double throttle = 0.5;
    double steer = 0.0;
    std::filesystem::path json, trace, record, svg;
    std::pair<std::string, std::string> save_at;  // T FILE
    std::filesystem::path resume;
};

// --save-at T FILE, checked.
struct SavePoint {
    double seconds;
    std::filesystem::path file;
};

// A lap that takes longer than this (simulated) means the car is stuck: give up.
constexpr double kMaxSecondsPerLap = 600.0;

void check_output(const std::filesystem::path& path, const char* option) {
    if (path.empty()) return;
    const std::filesystem::path folder = path.has_parent_path() ? path.parent_path() : ".";
    if (!std::filesystem::is_directory(folder))
        throw Error(std::string(option) + " '" + path.string() + "': folder '" + folder.string() +
                    "' does not exist");
}

// A progress bar on stderr, only when stderr is a terminal (never in logs or CI).
class Progress {
public:
    explicit Progress(double total) : total_(total), enabled_(total > 0.0 && isatty(2)) {}
    void show(double done, double speed_kmh) {
        if (!enabled_) return;
        const int percent = static_cast<int>(100.0 * std::min(done / total_, 1.0));
        if (percent == last_) return;
        last_ = percent;
        const int filled = percent / 4;
        std::fprintf(stderr, "\r[%.*s%*s] %3d%%  %6.1f km/h", filled, "#########################",
                     25 - filled, "", percent, speed_kmh);
        std::fflush(stderr);
    }
    ~Progress() {
        if (enabled_ && last_ >= 0) std::fprintf(stderr, "\n");
    }

private:
    double total_;
    bool enabled_;
    int last_ = -1;
};

std::optional<SavePoint> parse_save_at(const DriveOptions& o) {
    const auto& [time, file] = o.save_at;
    if (file.empty()) return std::nullopt;
    SavePoint point{0.0, file};
    std::size_t used = 0;
    try {
        point.seconds = std::stod(time, &used);
    } catch (const std::exception&) {
        used = 0;
    }
    if (used != time.size() || !std::isfinite(point.seconds) || point.seconds < 0.0)
        throw Error("--save-at '" + time + "': the time must be a finite number of seconds >= 0");
    if (o.seconds > 0.0 && point.seconds > o.seconds + 1e-9)
        throw Error("--save-at " + time + " is after the drive's end (--seconds " + std::to_string(o.seconds) + ")");
    check_output(point.file, "--save-at");
    return point;
}

void run(const DriveOptions& o) {
    const bool free_mode = !o.mesh.empty() || !o.spawn.empty();
    if (o.track != "default") throw Error("--track '" + o.track + "': the only generated track is 'default'");
    if (o.laps < 0) throw Error("--laps must be >= 0");
    if (o.seconds < 0.0 || !std::isfinite(o.seconds)) throw Error("--seconds must be finite and >= 0");
    if (!(o.target_speed_kmh > 0.0 && o.target_speed_kmh <= 1500.0))
        throw Error("--target-speed must be in (0, 1500] km/h");
    if (free_mode && o.spawn.empty()) throw Error("--mesh needs --spawn x,y,z to place the car");
    if (free_mode && o.laps > 0) throw Error("--laps needs the generated track (no centreline on a mesh); use --seconds");
    if (!o.spawn.empty() && o.spawn.size() != 3) throw Error("--spawn takes three numbers: x,y,z");
    for (const auto& [path, option] : {std::pair{o.json, "--json"}, {o.trace, "--trace"},
                                       {o.record, "--record"}, {o.svg, "--svg"}})
        check_output(path, option);
    const std::optional<SavePoint> save_at = parse_save_at(o);
    DriveSession session{free_mode, o.seed, o.target_speed_kmh, o.throttle, o.steer, {}, 0.0, 0.0, {}};
    std::optional<SnapshotFile> resume;
    if (!o.resume.empty()) {
        resume = load_snapshot(o.resume);
        const DriveSession saved = parse_session(resume->user_data);
        check_same_drive(saved, session);
        session = saved;
    }

    const DriveScene scene = o.mesh.empty() ? make_track_scene(o.seed) : make_mesh_scene(o.mesh);
    const CarSpec spec = CarSpec::default_car();
    World world(scene.statics);
    const RigidBodyState start =
        free_mode ? spawn_on_surface(*scene.statics, spec, {o.spawn[0], o.spawn[1], o.spawn[2]}, o.heading_deg)
                  : start_on_track(*scene.track, spec);
    world.add_car(spec, start);
    // Resuming: the same static world, settings and car (restore_state checks their
    // fingerprints), then the snapshot's state, update count and time.
    if (resume) world.restore_state(resume->world);

    std::optional<Autopilot> autopilot;
    if (!free_mode) {
        AutopilotSettings settings;
        settings.target_speed = o.target_speed_kmh / 3.6;
        autopilot.emplace(*scene.track, spec, settings);
        if (session.autopilot) autopilot->set_progress(*session.autopilot);
    }
    const int laps = !free_mode && o.laps == 0 && o.seconds == 0.0 ? 1 : o.laps;
    const double seconds = o.seconds > 0.0 ? o.seconds : laps * kMaxSecondsPerLap;

    std::unique_ptr<TraceRecorder> trace;
    if (!o.trace.empty()) {
        trace = std::make_unique<TraceRecorder>();
        world.set_trace(trace.get());
    }
    std::unique_ptr<RecordingWriter> recording;
    if (!o.record.empty())
        recording = std::make_unique<RecordingWriter>(o.record, world.settings().dt_update, 1, scene.description);

    DriveReport report;
    report.scene = scene.description;
    report.triangles = scene.triangle_count;
    report.distance_m = session.distance_m;
    report.top_speed_kmh = session.top_speed_kmh;
    report.lap_times_s = session.lap_times_s;
    DrivePlot plot;
    plot.dt = world.settings().dt_update;
    Progress progress(laps > 0 ? static_cast<double>(laps) : seconds);
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
        save_snapshot(save_at->file, world.save_state(), session_json(session));
        std::printf("snapshot     %s at %.2f s\n", save_at->file.string().c_str(), world.time());
        saved = true;
    };
    save_if_due();

    while (world.time() < seconds - 1e-9 && (laps == 0 || autopilot->laps() < laps)) {
        Car& car = world.car(0);
        car.set_inputs(autopilot ? autopilot->drive(car) : CarInputs{o.throttle, 0.0, o.steer});
        const int laps_before = autopilot ? autopilot->laps() : 0;
        world.update();
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
        plot.path.push_back(state.position);
        plot.speed_kmh.push_back(car.speed() * 3.6);
        plot.update_us.push_back(world.last_profile().update_us);
        if (recording) {
            recording->begin_frame(world.time(), world.state_hash());
            recording->add_car(state.position, state.orientation, car.speed(), world.contacts(0));
            recording->end_frame();
        }
        progress.show(laps > 0 ? autopilot->laps() + autopilot->distance_along() / scene.track->length_m -
                                     autopilot->laps()
                               : world.time(),
                      car.speed() * 3.6);
        save_if_due();
    }
    report.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
    report.updates = world.update_count();
    report.simulated_s = world.time();
    report.laps_completed = autopilot ? autopilot->laps() : 0;
    report.final_position = world.car(0).state().position;
    report.state_hash = world.state_hash();
    report.resets = world.car_resets(0);
    report.last_reset = world.last_reset_reason(0);

    print_drive_report(report);
    if (!o.json.empty()) write_drive_json(report, o.json);
    if (!o.svg.empty()) write_drive_svg(plot, scene.track, o.svg);
    if (trace) {
        std::ofstream out(o.trace, std::ios::binary);
        trace->write_chrome_trace(out);
        if (!out.flush()) throw Error("cannot write the trace '" + o.trace.string() + "'");
    }
    if (recording) recording->finish();
    if (save_at && !saved)
        throw Error("--save-at " + o.save_at.first + ": the drive ended at " + std::to_string(world.time()) +
                    " s, before that time; no snapshot written");
    if (laps > 0 && report.laps_completed < laps)
        throw Error("the car completed " + std::to_string(report.laps_completed) + " of " +
                    std::to_string(laps) + " laps in " + std::to_string(seconds) + " simulated seconds");
}

}  // namespace

void add_drive_command(CLI::App& app) {
    auto o = std::make_shared<DriveOptions>();
    CLI::App* command = app.add_subcommand(
        "drive", "Drive the default car: laps of a generated track by autopilot, or free on any mesh; "
                 "prints lap time, top speed and the per-phase profile of every update");
    command->add_option("--track", o->track, "Generated track to drive (default)")->capture_default_str();
    command->add_option("--seed", o->seed, "Seed of the generated track")->capture_default_str();
    command->add_option("--mesh", o->mesh, "Drive on this mesh file instead (free mode, needs --spawn)");
    command->add_option("--laps", o->laps, "Laps to drive by autopilot (default 1 without --seconds)");
    command->add_option("--seconds", o->seconds, "Simulated seconds to drive");
    command->add_option("--target-speed", o->target_speed_kmh, "Autopilot speed on straights (km/h)")
        ->capture_default_str();
    command->add_option("--spawn", o->spawn, "Free mode: start above x,y,z (the car lands on the surface below)")
        ->delimiter(',')
        ->expected(3);
    command->add_option("--heading", o->heading_deg, "Free mode: heading about +Y in degrees (0 = +X, 90 = -Z)")
        ->capture_default_str();
    command->add_option("--throttle", o->throttle, "Free mode: fixed throttle 0..1")->capture_default_str();
    command->add_option("--steer", o->steer, "Free mode: fixed steering -1..1 (+1 = left)")->capture_default_str();
    command->add_option("--json", o->json, "Write the figures as JSON");
    command->add_option("--trace", o->trace, "Write a Chrome trace (Perfetto) of every update's phases");
    command->add_option("--record", o->record, "Write car poses and contacts per update (JSON Lines) for a viewer");
    command->add_option("--svg", o->svg, "Plot the path over the track and the update times");
    command->add_option("--save-at", o->save_at,
                        "Save a snapshot to FILE when the simulated time reaches T seconds, and keep driving")
        ->type_name("T FILE");
    command->add_option("--resume", o->resume,
                        "Continue the drive saved in this snapshot (give the original drive's options; "
                        "--seconds and --laps count from the original start)")
        ->type_name("FILE");
    command->callback([o] { run(*o); });
}

}  // namespace trackphys::cli
