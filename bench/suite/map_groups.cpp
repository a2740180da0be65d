// Baked maps and many colliders (issue 18): the default track built as a World builds it,
// baked, written and loaded, with the bytes of each structure; a 165 km track's map (about
// 10 million triangles, the bigmap group, run only when named); and a car-box query over the
// same terrain in 50 and in 10,000 colliders (the top-level tree).

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <vector>

#include <unistd.h>

#include "bench_suite.hpp"
#include "trackphys/collision/mid_phase.hpp"
#include "trackphys/io/map_file.hpp"
#include "trackphys/track/track.hpp"

namespace trackphys::suite {
namespace {

using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// "12.3 ms": a duration for a target line's evidence.
std::string ms_text(double ms) {
    char text[32];
    std::snprintf(text, sizeof text, "%.1f ms", ms);
    return text;
}

// CPU time of every thread of this process (ns).
double process_cpu_ns() {
    timespec t{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return double(t.tv_sec) * 1e9 + double(t.tv_nsec);
}

// Medians over runs (ms): wall time, this thread's CPU time, and the whole process's CPU
// time (every thread's: what a threaded build costs on an idle machine, spread over its
// threads).
struct Timing {
    double wall_ms, cpu_ms, process_cpu_ms;
};

template <class F>
Timing median_ms(int repeats, F&& f) {
    std::vector<double> wall, cpu, process_cpu;
    for (int r = 0; r < repeats; ++r) {
        const double cpu_start = thread_cpu_ns(), process_start = process_cpu_ns();
        const auto start = Clock::now();
        f();
        wall.push_back(ms_since(start));
        cpu.push_back((thread_cpu_ns() - cpu_start) * 1e-6);
        process_cpu.push_back((process_cpu_ns() - process_start) * 1e-6);
    }
    return {spread(wall).median, spread(cpu).median, spread(process_cpu).median};
}

// A square terrain of side `cells` x 2 m cells (two triangles each), gently rolling, cut
// into tiles x tiles meshes in row order.
std::vector<TriangleMesh> terrain_tiles(int cells, int tiles) {
    std::vector<TriangleMesh> meshes;
    const int per_tile = cells / tiles;
    const auto height = [](int i, int j) { return 0.5 * std::sin(i * 0.05) * std::cos(j * 0.07); };
    for (int ti = 0; ti < tiles; ++ti)
        for (int tj = 0; tj < tiles; ++tj) {
            TriangleMesh& m = meshes.emplace_back();
            const int n = per_tile + 1;
            for (int i = 0; i < n; ++i)
                for (int j = 0; j < n; ++j) {
                    const int gi = ti * per_tile + i, gj = tj * per_tile + j;
                    m.vertices.push_back({2.0 * gi, height(gi, gj), 2.0 * gj});
                }
            for (int i = 0; i < per_tile; ++i)
                for (int j = 0; j < per_tile; ++j) {
                    const auto v = static_cast<std::uint32_t>(i * n + j);
                    const auto w = static_cast<std::uint32_t>(n);
                    m.triangles.push_back({v, v + 1, v + w + 1});
                    m.triangles.push_back({v, v + w + 1, v + w});
                }
        }
    return meshes;
}

// One collider per mesh, built in memory.
std::shared_ptr<StaticWorld> world_of(const std::vector<TriangleMesh>& meshes) {
    auto world = std::make_shared<StaticWorld>();
    for (const TriangleMesh& m : meshes) world->add(std::make_shared<StaticCollider>(m));
    return world;
}

// The same colliders baked, written and loaded back (arrays allocated collider after
// collider, each followed by its plane tree).
StaticMap loaded_from_a_map_file(const std::vector<TriangleMesh>& meshes) {
    const std::filesystem::path file =
        std::filesystem::temp_directory_path() /
        ("trackphys-bench-tiles-" + std::to_string(::getpid()) + ".tpmap");
    save_map(file, bake_map(meshes, PlaneTreeSettings::precomputed(), 2));
    StaticMap loaded = load_static_world(file);
    std::filesystem::remove(file);
    return loaded;
}

// The terrain triangle a (collider, triangle) of terrain_tiles(cells, tiles) is, numbered as in
// one collider over the whole terrain: the same triangle in any tiling has the same number.
std::uint32_t terrain_triangle(const TriangleRef& ref, int cells, int tiles) {
    const auto per_tile = static_cast<std::uint32_t>(cells / tiles);
    const std::uint32_t ti = ref.collider / std::uint32_t(tiles),
                        tj = ref.collider % std::uint32_t(tiles);
    const std::uint32_t cell = ref.triangle / 2, i = cell / per_tile, j = cell % per_tile;
    return 2 * ((ti * per_tile + i) * std::uint32_t(cells) + tj * per_tile + j) + ref.triangle % 2;
}

// The bytes of a file (empty when it cannot be read).
std::string bytes_of(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Whether a load of `file` on `threads` threads encodes back to `baked_bytes`, the bytes of
// the map it was written from: the load lines are met only for a load that lost nothing.
bool loaded_map_is_the_file(const std::filesystem::path& file, unsigned threads,
                            const std::string& baked_bytes) {
    return encode_map(load_static_world(file, PlaneTreeSettings::precomputed(), threads)) ==
           baked_bytes;
}

// Whether two static worlds hold the same colliders in the same order: the same kept
// triangles, vertices and surface ids (content_hash), and the same bounds and BVH size.
bool same_colliders(const StaticWorld& a, const StaticWorld& b) {
    if (a.size() != b.size()) return false;
    for (std::uint32_t id = 0; id < a.size(); ++id) {
        const StaticCollider &x = a.collider(id), &y = b.collider(id);
        if (x.content_hash() != y.content_hash() || x.bounds().min != y.bounds().min ||
            x.bounds().max != y.bounds().max || x.bytes_used() != y.bytes_used())
            return false;
    }
    return true;
}

// Queries on which two tilings of the terrain report different sets of triangles.
std::size_t queries_that_differ(const StaticWorld& a, int tiles_a, const StaticWorld& b,
                                int tiles_b, int cells, const std::vector<Aabb>& boxes) {
    std::size_t differ = 0;
    std::vector<TriangleRef> refs;
    const auto found = [&](const StaticWorld& w, int tiles, const Aabb& box) {
        refs.clear();
        w.query_aabb(box, refs);
        std::vector<std::uint32_t> triangles;
        for (const TriangleRef& ref : refs)
            triangles.push_back(terrain_triangle(ref, cells, tiles));
        std::sort(triangles.begin(), triangles.end());
        return triangles;
    };
    for (const Aabb& box : boxes)
        if (found(a, tiles_a, box) != found(b, tiles_b, box)) ++differ;
    return differ;
}

}  // namespace

void bench_maps(BenchRun& run) {
    run.progress("maps", "generating the default track");
    TrackParams params;
    params.seed = kDemoTrackSeed;
    const Track track = generate_track(params);
    const double triangles = double(track.triangle_count());

    run.progress("maps", "building as a World does");
    StaticWorld built;
    ColliderPlaneTrees built_trees;
    const Timing build = median_ms(1, [&] {
        for (const TrackChunk& chunk : track.chunks)
            built.add(std::make_shared<StaticCollider>(chunk.mesh));
        built_trees = make_collider_plane_trees(built, PlaneTreeSettings::precomputed(), 1);
    });
    std::size_t collider_bytes = 0, tree_bytes = 0;
    for (std::uint32_t id = 0; id < built.size(); ++id) {
        collider_bytes += built.collider(id).bytes_used();
        tree_bytes += built_trees[id]->bytes_used();
    }

    run.progress("maps", "baking");
    StaticMap map;
    const Timing bake = median_ms(run.batches(1, 3), [&] {
        map = bake_track_map(track, PlaneTreeSettings::precomputed(), 2);
    });
    const std::filesystem::path file = std::filesystem::temp_directory_path() /
                                       ("trackphys-bench-" + std::to_string(::getpid()) + ".tpmap");
    const Timing save = median_ms(1, [&] { save_map(file, map); });
    const double file_bytes = double(std::filesystem::file_size(file));

    run.progress("maps", "loading");
    const auto load_on = [&](unsigned threads) {
        return median_ms(run.batches(3, 11), [&] {
            keep(
                load_static_world(file, PlaneTreeSettings::precomputed(), threads).statics->size());
        });
    };
    const Timing load = load_on(1), load_2 = load_on(2);
    const std::string baked_bytes = encode_map(map);
    const bool loads_what_was_baked = loaded_map_is_the_file(file, 2, baked_bytes);
    std::filesystem::remove(file);
    const bool bakes_what_a_world_builds = same_colliders(*map.statics, built);

    BenchRow& build_row =
        run.add("maps", "default track: build colliders + plane trees", build.wall_ms * 1e6);
    build_row.figures = {{"triangles", triangles},
                         {"cpu_ms", build.cpu_ms},
                         {"collider_bytes_per_triangle", double(collider_bytes) / triangles},
                         {"plane_tree_bytes_per_triangle", double(tree_bytes) / triangles}};
    build_row.note = "what World does at start, on one thread";
    BenchRow& bake_row = run.add("maps", "default track: bake (2 threads)", bake.wall_ms * 1e6,
                                 "default track: build colliders + plane trees");
    bake_row.figures = {{"cpu_ms_all_threads", bake.process_cpu_ms}, {"write_ms", save.wall_ms}};
    BenchRow& load_row = run.add("maps", "default track: load the map", load.wall_ms * 1e6,
                                 "default track: build colliders + plane trees");
    load_row.figures = {{"cpu_ms", load.cpu_ms},
                        {"wall_ms_2_threads", load_2.wall_ms},
                        {"cpu_ms_all_threads_2_threads", load_2.process_cpu_ms},
                        {"file_bytes_per_triangle", file_bytes / triangles}};
    load_row.note = "on 1 thread: file read, arrays copied and verified, plane-tree frames derived";
    // The CPU time of a load on one thread: all the work a load does, which wall time on a
    // shared machine inflates and a second thread would hide.
    run.add_target("default track: load a baked map <= 50 ms (CPU, 1 thread)", 50.0 / load.cpu_ms,
                   1.0, loads_what_was_baked,
                   ms_text(load.cpu_ms) + " CPU, " + ms_text(load.wall_ms) +
                       " wall; on 2 threads " + ms_text(load_2.wall_ms) + " wall; the loaded map " +
                       (loads_what_was_baked ? "encodes" : "does NOT encode") +
                       " to the baked one's bytes");
    // Wall time, as the issue asks; the evidence adds the CPU time of both threads, half of
    // which is the wall time the bake needs on two idle cores.
    run.add_target(
        "default track: bake <= 0.5 s", 500.0 / bake.wall_ms, 1.0, bakes_what_a_world_builds,
        ms_text(bake.wall_ms) + " on 2 threads (" + ms_text(bake.process_cpu_ms) +
            " CPU over both); its colliders " + (bakes_what_a_world_builds ? "are" : "are NOT") +
            " the ones a World builds");
}

void bench_big_map(BenchRun& run) {
    // 165 km of the generated track: about 9.7 million triangles in 1,650 colliders.
    run.progress("bigmap", "generating a 165 km track");
    TrackParams params;
    params.seed = kDemoTrackSeed;
    params.length_m = 165000.0;
    const Track track = generate_track(params);
    const double triangles = double(track.triangle_count());

    run.progress("bigmap", "baking");
    StaticMap map;
    const Timing bake =
        median_ms(1, [&] { map = bake_track_map(track, PlaneTreeSettings::precomputed(), 2); });
    const std::filesystem::path file =
        std::filesystem::temp_directory_path() /
        ("trackphys-bench-big-" + std::to_string(::getpid()) + ".tpmap");
    save_map(file, map);
    const double file_bytes = double(std::filesystem::file_size(file));
    map = {};

    run.progress("bigmap", "loading");
    std::size_t collider_bytes = 0, tree_bytes = 0;
    const Timing load = median_ms(run.batches(1, 3), [&] {
        const StaticMap loaded = load_static_world(file, PlaneTreeSettings::precomputed(), 1);
        collider_bytes = tree_bytes = 0;
        for (std::uint32_t id = 0; id < loaded.statics->size(); ++id) {
            collider_bytes += loaded.statics->collider(id).bytes_used();
            tree_bytes += loaded.plane_trees[id]->bytes_used();
        }
    });
    const Timing load_2 = median_ms(run.batches(1, 3), [&] {
        keep(load_static_world(file, PlaneTreeSettings::precomputed(), 2).statics->size());
    });
    run.progress("bigmap", "checking the load against the file");
    const bool loads_what_was_baked = loaded_map_is_the_file(file, 2, bytes_of(file));
    std::filesystem::remove(file);
    const double resident = double(collider_bytes + tree_bytes) / triangles;

    BenchRow& bake_row = run.add("bigmap", "165 km track: bake (2 threads)", bake.wall_ms * 1e6);
    bake_row.figures = {{"triangles", triangles}, {"cpu_ms_all_threads", bake.process_cpu_ms}};
    BenchRow& load_row = run.add("bigmap", "165 km track: load the map", load.wall_ms * 1e6,
                                 "165 km track: bake (2 threads)");
    load_row.figures = {{"cpu_ms", load.cpu_ms},
                        {"wall_ms_2_threads", load_2.wall_ms},
                        {"cpu_ms_all_threads_2_threads", load_2.process_cpu_ms},
                        {"file_bytes_per_triangle", file_bytes / triangles},
                        {"collider_bytes_per_triangle", double(collider_bytes) / triangles},
                        {"plane_tree_bytes_per_triangle", double(tree_bytes) / triangles}};
    const bool big_enough = triangles >= 9.5e6;
    run.add_target("10M-triangle map: bake <= 30 s on 2 cores", 30e3 / bake.wall_ms, 1.0,
                   big_enough,
                   ms_text(bake.wall_ms) + " wall (" + ms_text(bake.process_cpu_ms) +
                       " CPU over both threads)");
    // Judged like the bake, on the two cores: the wall time of a load on 2 threads
    // (load_static_world's default uses every core). One thread's CPU time, the whole work
    // of a load, is the evidence beside it: on a shared machine it is the steadier figure.
    run.add_target(
        "10M-triangle map: load <= 0.5 s on 2 cores", 500.0 / load_2.wall_ms, 1.0,
        big_enough && loads_what_was_baked,
        ms_text(load_2.wall_ms) + " wall on 2 threads; on 1 thread " + ms_text(load.cpu_ms) +
            " CPU, " + ms_text(load.wall_ms) + " wall; the loaded map " +
            (loads_what_was_baked ? "encodes" : "does NOT encode") + " to the file's bytes");
    char resident_text[96];
    std::snprintf(resident_text, sizeof resident_text, "%.1f bytes a triangle over %.0f triangles",
                  resident, triangles);
    run.add_target("10M-triangle map: BVH + plane trees + vertices <= 100 bytes a triangle",
                   100.0 / resident, 1.0, big_enough, resident_text);
}

void bench_many_colliders(BenchRun& run) {
    // 700 x 700 cells of 2 m, 980,000 triangles, as 49 (7 x 7, the square nearest 50) and
    // as 10,000 (100 x 100) colliders.
    constexpr int kCells = 700, kFewTiles = 7, kManyTiles = 100;
    run.progress("colliders", "building 49 colliders");
    const auto few = world_of(terrain_tiles(kCells, kFewTiles));
    run.progress("colliders", "building 10,000 colliders");
    const std::vector<TriangleMesh> tiles = terrain_tiles(kCells, kManyTiles);
    const auto many = world_of(tiles);
    run.progress("colliders", "baking and loading 10,000 colliders");
    const StaticMap map = loaded_from_a_map_file(tiles);
    const StaticWorld& loaded = *map.statics;
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> where(10.0, 2.0 * kCells - 10.0);
    std::vector<Aabb> boxes;
    for (int i = 0; i < 1000; ++i) {
        const glm::dvec3 c(where(rng), 0.0, where(rng));
        boxes.push_back(Aabb{c - glm::dvec3(2.5, 1.5, 2.5), c + glm::dvec3(2.5, 1.5, 2.5)});
    }
    std::vector<TriangleRef> refs;
    std::size_t found_few = 0, found_many = 0, found_loaded = 0;
    const auto query = [&](const StaticWorld& w, std::size_t& found) {
        return [&] {
            found = 0;
            for (const Aabb& b : boxes) {
                refs.clear();
                w.query_aabb(b, refs);
                found += refs.size();
            }
            keep(refs.data());
        };
    };
    // What StaticWorld did before its tree: every collider's box, then the hit ones' BVHs.
    std::size_t found_loop = 0;
    const auto loop = [&] {
        found_loop = 0;
        for (const Aabb& b : boxes) {
            refs.clear();
            for (std::uint32_t id = 0; id < many->size(); ++id)
                if (many->collider(id).bounds().overlaps(b))
                    many->collider(id).query_aabb_refs(b, id, refs);
            found_loop += refs.size();
        }
        keep(refs.data());
    };
    run.progress("colliders", "car-box queries");
    // Thread CPU time: in wall time, on a loaded machine, the 10,000-collider batches (the
    // longer ones) were interrupted by other processes more often, which alone made the
    // ratio 3-10x in runs where CPU time said 1.5x.
    const std::vector<double> ns = median_call_cpu_ns_in_turns(
        {query(*few, found_few), query(*many, found_many), query(loaded, found_loaded)}, 1,
        run.batches(5, 31));
    // Apart: its 10,000 boxes a query would leave the others' data cold.
    const double loop_ns = median_call_ns(loop, 1, run.batches(3, 5));
    const double per_query_few = ns[0] / double(boxes.size()),
                 per_query_many = ns[1] / double(boxes.size()),
                 per_query_loaded = ns[2] / double(boxes.size());
    run.add("colliders", "car box, 49 colliders", per_query_few).figures = {
        {"triangles_found", double(found_few)}};
    run.add("colliders", "car box, 10,000 colliders", per_query_many, "car box, 49 colliders")
        .figures = {{"triangles_found", double(found_many)}};
    BenchRow& loaded_row = run.add("colliders", "car box, 10,000 colliders from a map file",
                                   per_query_loaded, "car box, 49 colliders");
    loaded_row.figures = {{"triangles_found", double(found_loaded)}};
    loaded_row.note = "baked, written, loaded";
    run.add("colliders", "car box, 10,000 colliders, every box tested",
            loop_ns / double(boxes.size()), "car box, 49 colliders")
        .note = "StaticWorld before its top-level tree";
    // Met only if the built and the loaded 10,000 colliders both are within 2x, and both
    // found the 49 colliders' terrain triangles on every query.
    const std::size_t differ =
        queries_that_differ(*few, kFewTiles, *many, kManyTiles, kCells, boxes);
    const std::size_t differ_loaded =
        queries_that_differ(*few, kFewTiles, loaded, kManyTiles, kCells, boxes);
    char evidence[200];
    std::snprintf(evidence, sizeof evidence,
                  "built %.2fx, loaded %.2fx; %zu / %zu / %zu triangles; %zu and %zu of %zu "
                  "queries differ",
                  per_query_many / per_query_few, per_query_loaded / per_query_few, found_few,
                  found_many, found_loaded, differ, differ_loaded, boxes.size());
    run.add_target("10,000 colliders: car-box query within 2x of 50",
                   2.0 * per_query_few / std::max(per_query_many, per_query_loaded), 1.0,
                   differ == 0 && differ_loaded == 0, evidence);
}

}  // namespace trackphys::suite
