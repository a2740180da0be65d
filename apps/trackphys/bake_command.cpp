// `trackphys bake MESH|--seed S --out MAP.tpmap`: builds every collider's BVH and plane tree
// once and writes them to a map file that drive --map loads without rebuilding.

#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>

#include "collider_build.hpp"
#include "commands.hpp"
#include "file_clashes.hpp"
#include "interrupt_guard.hpp"
#include "staged_outputs.hpp"
#include "trackphys/error.hpp"
#include "trackphys/io/map_file.hpp"
#include "trackphys/track/track.hpp"

namespace trackphys::cli {
namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

void run_bake(const BakeOptions& o, const OptionGiven& given) {
    const bool from_mesh = !o.mesh.empty();
    if (from_mesh && given("--seed"))
        throw Error("give a mesh file or --seed (a generated track), not both");
    if (!from_mesh) refuse_unused_mesh_limits(given, "bake", "the generated track of --seed");
    if (!from_mesh && given("--chunk"))
        throw Error("--chunk splits a mesh file; a generated track comes in its own chunks");
    if (!(std::isfinite(o.chunk_m) && o.chunk_m > 0.0))
        throw Error("--chunk must be finite and > 0 m, got " + exact_text(o.chunk_m));
    check_threads(o.threads);
    if (o.out.extension() != ".tpmap")
        throw Error("--out '" + o.out.string() + "': a map file's name ends in .tpmap");
    refuse_file_clashes({{"MESH", o.mesh}}, {{"--out", o.out}});
    // Ctrl-C stops the bake at the next collider built, or at the next report of a mesh
    // file's placing (build_mesh_colliders), and the staged file is removed, rather than the
    // process killed and the file left behind.
    const InterruptGuard interrupt_guard;
    // Staged before the build, so that an --out the folder will not take is refused before
    // seconds of work rather than after them.
    StagedOutputs outputs;
    const std::filesystem::path staged = outputs.stage(o.out, "--out");
    const auto start = std::chrono::steady_clock::now();
    const auto threads = static_cast<unsigned>(o.threads);
    StaticMap map;
    std::string source;
    if (from_mesh) {
        map = build_mesh_colliders(o.mesh, o.mesh_limits, o.chunk_m, threads);
        source = "mesh " + o.mesh.string();
    } else {
        TrackParams params;
        params.seed = o.seed;
        map = build_track_colliders(generate_track(params), threads);
        source = "generated track, seed " + std::to_string(o.seed);
    }
    const double bake_s = seconds_since(start);
    const auto write_start = std::chrono::steady_clock::now();
    try {
        save_map(staged, map);
    } catch (const Error& e) {  // its words name the staged file, which the user never named
        throw Error("--out '" + o.out.string() + "': " + e.what());
    }
    InterruptGuard::check();
    outputs.commit();
    const double write_s = seconds_since(write_start);

    std::size_t triangles = 0, kept = 0;
    for (std::uint32_t id = 0; id < map.statics->size(); ++id) {
        triangles += map.statics->collider(id).mesh_triangle_count();
        kept += map.statics->collider(id).triangle_count();
    }
    const auto bytes = std::filesystem::file_size(o.out);
    std::printf("baked        %s\n", source.c_str());
    std::printf("colliders    %zu, %zu triangles (%zu kept)\n", map.statics->size(), triangles,
                kept);
    std::printf("map          %s, %.1f MB, %.1f bytes a triangle\n", o.out.string().c_str(),
                double(bytes) / 1e6, kept > 0 ? double(bytes) / double(kept) : 0.0);
    std::printf("time         %.3f s to build, %.3f s to write\n", bake_s, write_s);
}

}  // namespace trackphys::cli
