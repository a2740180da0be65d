// The command line of `trackphys`: every subcommand's options, help texts and checks on
// their text, read into the option structs of commands.hpp, and the callbacks that run the
// commands. The only file besides main.cpp that includes CLI11 (see commands.hpp).

#include "command_line.hpp"

#include <cstddef>
#include <limits>
#include <memory>
#include <string>

#include "commands.hpp"
#include "trackphys/io/mesh_load_limits.hpp"

namespace trackphys::cli {
namespace {

// Rejects a leading minus sign: CLI11 reads "-1" into an unsigned option as 2^64 - 1.
CLI::Validator not_negative() {
    return CLI::Validator(
        [](const std::string& text) {
            return text.rfind('-', 0) == 0 ? std::string("must be >= 0, got " + text) : "";
        },
        "UINT", "not_negative");
}

// A limit of 0 would refuse every mesh; a leading minus sign CLI11 would wrap into an
// unsigned option as 2^64 - 1.
CLI::Validator at_least_one() {
    return CLI::Validator(
        [](const std::string& text) {
            const bool positive =
                !text.empty() && text[0] != '-' && text.find_first_not_of('0') != std::string::npos;
            return positive ? std::string() : "must be >= 1, got " + text;
        },
        "", "at_least_one");
}

// Whether command's line gave an option: valid while command lives, which is the whole run.
OptionGiven given_on(const CLI::App& command) {
    return [&command](const std::string& option) { return command.count(option) > 0; };
}

// Adds --max-triangles, --max-vertices, --max-bytes and --max-nesting (MeshLoadLimits,
// defaults shown in --help) to a command that loads mesh files, in an option group of their
// own, writing into limits.
void add_mesh_limit_options(CLI::App& command, MeshLoadLimits& limits) {
    const std::string group = "Mesh limits (a mesh file beyond one is refused)";
    command.add_option("--max-triangles", limits.max_triangles, "triangles in the loaded mesh")
        ->group(group)
        ->check(at_least_one())
        ->capture_default_str();
    command.add_option("--max-vertices", limits.max_vertices, "vertices in the loaded mesh")
        ->group(group)
        ->check(at_least_one())
        ->capture_default_str();
    command
        .add_option("--max-bytes", limits.max_bytes,
                    "bytes of the mesh file and the glTF buffer files it names")
        ->group(group)
        ->check(at_least_one())
        ->capture_default_str();
    command
        .add_option("--max-polygon-corners", limits.max_polygon_corners,
                    "corners of one polygon (its triangulation's time grows with their square)")
        ->group(group)
        ->check(CLI::Range(std::size_t{3}, std::numeric_limits<std::size_t>::max()))
        ->capture_default_str();
    command
        .add_option("--max-nesting", limits.max_nesting, "nesting of AC3D objects and glTF nodes")
        ->group(group)
        ->check(CLI::Range(std::size_t{1}, max_mesh_nesting_allowed))
        ->capture_default_str();
}

// "G0,G1,..." as grips, each element a number: an empty or non-numeric one is a conversion
// error naming the surface.
std::vector<double> grips_of(const std::string& list) {
    std::vector<double> grips;
    std::size_t start = 0;
    for (std::size_t id = 0;; ++id) {
        const std::size_t comma = std::min(list.find(',', start), list.size());
        const std::string element = list.substr(start, comma - start);
        double grip = 0.0;
        if (!CLI::detail::lexical_cast(element, grip))
            throw CLI::ConversionError(
                "Could not convert: --surface-grips = " + list + ": surface " + std::to_string(id) +
                "'s grip " +
                (element.empty() ? "is missing" : "'" + element + "' is not a number"));
        grips.push_back(grip);
        if (comma == list.size()) return grips;
        start = comma + 1;
    }
}

void add_surface_grips_option(CLI::App& command, std::vector<double>& grips) {
    // Split by grips_of rather than by CLI11's delimiter, which drops empty elements: "1,,0.2"
    // would grip surface 1 at 0.2 where the user meant surface 2. Values given apart ("1 0.5",
    // or the option twice) continue the list, as they did with the delimiter.
    command
        .add_option_function<std::vector<std::string>>(
            "--surface-grips",
            [&grips](const std::vector<std::string>& values) {
                std::string list;
                for (const std::string& value : values) list += (list.empty() ? "" : ",") + value;
                grips = grips_of(list);
            },
            "Grip of the track's surfaces by id, from 0 (`trackphys info MESH` lists a "
            "mesh's; the generated track's road 0, walls 1); the ids past them grip 1, "
            "the dry road")
        ->type_name("G0,G1,...");
}

void add_drive_command(CLI::App& app) {
    auto o = std::make_shared<DriveOptions>();
    CLI::App* command = app.add_subcommand(
        "drive",
        "Drive the default car (or --car, or a --scenario file): laps of a generated track by "
        "autopilot, or free on any mesh; prints lap time, top speed and the per-phase profile of "
        "every update. Options given with --scenario override the file's values");
    command->add_option("--scenario", o->scenario_file,
                        "Read track, car, driver and duration from this JSON file (see "
                        "docs/cli.md, 'Car spec and scenario files')");
    CLI::Option* car_file = command->add_option(
        "--car", o->car_file, "Read the car spec from this JSON file (see --print-car)");
    command
        ->add_option("--car-preset", o->car_preset,
                     "Drive a preset car: arcade (the default car), gt or formula "
                     "(docs/vehicle.md); in a --car file, \"model\" picks one")
        ->excludes(car_file);
    CLI::Option* print_car = command->add_flag(
        "--print-car", o->print_car,
        "Print the car spec (default, --car or the scenario's) as JSON and exit: a starting "
        "point for a --car file");
    command
        ->add_flag(
            "--print-scenario", o->print_scenario,
            "Print the scenario these options describe as JSON and exit: a starting point for a "
            "--scenario file")
        ->excludes(print_car);
    command->add_option("--track", o->track, "Generated track to drive (default)")
        ->capture_default_str();
    command->add_option("--seed", o->flags.seed, "Seed of the generated track")
        ->check(not_negative())
        ->capture_default_str();
    command->add_option("--mesh", o->flags.mesh,
                        "Drive on this mesh file instead (free mode, needs --spawn and --seconds)");
    command->add_option(
        "--map", o->flags.map,
        "Drive on this baked map (trackphys bake): by autopilot when it was "
        "baked from a generated track, else in free mode (needs --spawn and --seconds)");
    command->add_option(
        "--laps", o->flags.laps,
        "Laps to drive by autopilot, 1 to 1000 (default 1 without --seconds; with it, "
        "the drive fails if the time ends first)");
    command->add_option("--seconds", o->flags.seconds, "Simulated seconds to drive (> 0)");
    command
        ->add_option("--target-speed", o->flags.target_speed_kmh,
                     "Autopilot speed on straights (km/h)")
        ->capture_default_str();
    command
        ->add_option("--spawn", o->spawn,
                     "Free mode: start above x,y,z (the car lands on the surface below)")
        ->delimiter(',')
        ->expected(3);
    add_surface_grips_option(*command, o->surface_grips);
    command
        ->add_option("--heading", o->flags.heading_deg,
                     "Free mode: heading about +Y in degrees (0 = +X, 90 = -Z)")
        ->capture_default_str();
    command
        ->add_option("--throttle", o->flags.inputs.throttle,
                     "Free mode: fixed throttle -1..1 (< 0: reverse, once nearly stopped)")
        ->capture_default_str();
    command
        ->add_option("--steer", o->flags.inputs.steer,
                     "Free mode: fixed steering -1..1 (+1 = left)")
        ->capture_default_str();
    command->add_option("--json", o->json, "Write the figures as JSON");
    command->add_option("--trace", o->trace,
                        "Write a Chrome trace (Perfetto) of every update's phases");
    command->add_option(
        "--record", o->record,
        "Write car poses, contacts and vehicle telemetry per update (JSON Lines) for a "
        "viewer");
    command->add_option("--telemetry", o->telemetry,
                        "Write per-update telemetry as CSV with named channels (speed, inputs; "
                        "with a vehicle model rpm, gear and each wheel's slip, load and spin)");
    command->add_option("--svg", o->svg, "Plot the path over the track and the update times");
    command
        ->add_option(
            "--save-at", o->save_at,
            "Save a snapshot to FILE when the simulated time reaches T seconds, and keep driving")
        ->type_name("T FILE");
    command
        ->add_option(
            "--resume", o->resume,
            "Continue the drive saved in this snapshot (give the original drive's options; "
            "--seconds and --laps count from the original start)")
        ->type_name("FILE");
    add_mesh_limit_options(*command, o->mesh_limits);
    command->callback([o, command] { run_drive(*o, given_on(*command)); });
}

void add_race_command(CLI::App& app) {
    auto o = std::make_shared<RaceOptions>();
    CLI::App* command = app.add_subcommand(
        "race",
        "Race a field of default cars on a generated track: a two-column grid, each car on its "
        "own autopilot and target speed, passing slower cars on the side; the cars collide. "
        "Prints the classification and the per-update profile of the whole world");
    command->add_option("--scenario", o->scenario_file,
                        "Race a scenario file: its track seed, car (every car's), cars, "
                        "autopilot target speed (the fastest car's), laps and seconds; options "
                        "given with it override the file's values");
    command->add_option("--seed", o->seed, "Seed of the generated track")
        ->check(not_negative())
        ->capture_default_str();
    command->add_option("--map", o->map,
                        "Race on this baked map (trackphys bake --seed) instead of generating "
                        "the track");
    add_surface_grips_option(*command, o->surface_grips);
    command->add_option("--cars", o->cars, "Cars on the grid (1 to 128)")
        ->check(at_least_one())
        ->capture_default_str();
    command->add_option(
        "--laps", o->laps,
        "Laps every car must complete, 1 to 1000 (default 1 without --seconds; with "
        "it, the race fails if the time ends first)");
    command->add_option("--seconds", o->seconds, "Simulated seconds to race (> 0)");
    command
        ->add_option("--threads", o->threads,
                     "Threads to update the world on (0: the hardware's count)")
        ->capture_default_str();
    command->add_option("--json", o->json, "Write the figures as JSON");
    command->add_option("--trace", o->trace,
                        "Write a Chrome trace (Perfetto) of the updates; runs them on one "
                        "thread, since a trace records only the calling thread's");
    command->add_option("--svg", o->svg,
                        "Plot every car's path over the track and the update times");
    command->add_option("--record", o->record,
                        "Write every car's pose, contacts and (gt, formula) vehicle telemetry per "
                        "update (JSON Lines) for a viewer");
    command->callback([o, command] { run_race(*o, given_on(*command)); });
}

void add_track_command(CLI::App& app) {
    auto options = std::make_shared<TrackOptions>();
    TrackParams& p = options->params;
    p.seed = kDemoTrackSeed;
    CLI::App* command = app.add_subcommand(
        "track",
        "Generate a closed, banked race track (Bezier loop) and print its figures; "
        "optionally write its mesh and a top-view picture");
    command->add_option("--seed", p.seed, "Random seed (same seed, same track)")
        ->check(not_negative())
        ->capture_default_str();
    // Each parameter's flag, and the TrackParams field it sets: the generator's errors name
    // the field, the command's the flag.
    const auto add_param = [&](const char* flag, const char* field, auto& value, const char* help) {
        options->flag_of_field.emplace_back(field, flag);
        command->add_option(flag, value, help)->capture_default_str();
    };
    add_param("--length", "length_m", p.length_m, "Centreline length (m)");
    add_param("--width", "width_m", p.width_m, "Road width (m)");
    add_param("--max-bank", "max_bank_deg", p.max_bank_deg, "Largest bank angle (degrees)");
    add_param("--full-bank-radius", "full_bank_radius_m", p.full_bank_radius_m,
              "Turns this tight or tighter get the full bank (m)");
    add_param("--elevation", "elevation_amplitude_m", p.elevation_amplitude_m,
              "Height amplitude of the control points (m)");
    add_param("--wall-height", "wall_height_m", p.wall_height_m, "Wall height (m)");
    add_param("--min-radius", "min_turn_radius_m", p.min_turn_radius_m,
              "Tightest allowed turn radius (m)");
    add_param("--edge-tight", "edge_tight_m", p.edge_tight_m,
              "Density: road edge length along the track in tight turns (m)");
    add_param("--edge-straight", "edge_straight_m", p.edge_straight_m,
              "Density: road edge length on straights (m)");
    add_param("--tight-radius", "tight_radius_m", p.tight_radius_m,
              "Density: turns this tight or tighter get --edge-tight (m)");
    add_param("--strips", "strips", p.strips, "Density: road strips across the width");
    add_param("--chunk-length", "chunk_length_m", p.chunk_length_m,
              "Collider chunk length along the track (m)");
    command->add_option("--out", options->out,
                        "Write the track mesh (FILE.glb, .gltf, .obj, .ply or .stl)");
    command->add_option("--svg", options->svg,
                        "Write a top view coloured by bank angle (FILE.svg)");
    command->callback([options] { run_track(*options); });
}

void add_info_command(CLI::App& app) {
    CLI::App* command = app.add_subcommand(
        "info",
        "Read a mesh file (glTF/GLB, OBJ, PLY, STL, AC3D or OFF) "
        "the way a static collider would, and print its triangle and vertex counts, bounds, "
        "area and what was dropped (degenerate triangles, points, lines); or describe a baked "
        "map (trackphys bake): format, build options, colliders, memory, track");
    auto options = std::make_shared<InfoOptions>();
    command->add_option("MESHFILE", options->file, "the mesh file or map file (.tpmap) to read")
        ->required();
    command->add_flag("--json", options->json, "print the figures as one JSON object");
    add_mesh_limit_options(*command, options->mesh_limits);
    command->callback([options] { run_info(*options); });
}

void add_bake_command(CLI::App& app) {
    auto o = std::make_shared<BakeOptions>();
    CLI::App* command = app.add_subcommand(
        "bake",
        "Build every collider's BVH and plane tree once, for a mesh file (split into --chunk "
        "cells, one collider each) or a generated track (--seed, one collider per chunk), and "
        "write them to a map file that `drive --map` loads without rebuilding");
    command->add_option("MESH", o->mesh, "the mesh file to bake (any format `info` reads)");
    command->add_option("--seed", o->seed, "bake the generated track of this seed instead")
        ->check(not_negative())
        ->capture_default_str();
    command->add_option("--out", o->out, "the map file to write (MAP.tpmap)")->required();
    command->add_option("--chunk", o->chunk_m, "a mesh's collider cells on x and z (m, > 0)")
        ->capture_default_str();
    command->add_option("--threads", o->threads, "threads to build on, 0 to 256 (0: one per core)")
        ->capture_default_str();
    add_mesh_limit_options(*command, o->mesh_limits);
    command->callback([o, command] { run_bake(*o, given_on(*command)); });
}

void add_bench_command(CLI::App& app) {
    CLI::App* command = app.add_subcommand(
        "bench",
        "Moved: the benchmark suite is the trackphys-bench program (built with the benchmarks)");
    command->allow_extras();
    command->callback([] { run_bench(); });
}

void add_view_command(CLI::App& app) {
    auto o = std::make_shared<ViewOptions>();
    CLI::App* command = app.add_subcommand(
        "view",
        "Write a self-contained HTML page that replays a recording (drive --record) in a 3D "
        "viewer: open it in a browser, no server or network needed");
    command->add_option("RECORDING", o->recording, "The recording (JSON Lines)")->required();
    command->add_option("--out", o->out, "The page to write (.html)")->required();
    add_mesh_limit_options(*command, o->mesh_limits);
    command->callback([o] { run_view(*o); });
}

}  // namespace

void add_commands(CLI::App& app) {
    add_drive_command(app);
    add_race_command(app);
    add_track_command(app);
    add_info_command(app);
    add_bake_command(app);
    add_bench_command(app);
    add_view_command(app);
}

}  // namespace trackphys::cli
