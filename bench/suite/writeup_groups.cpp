// The write-up's improvements, each as before/after on the same inputs: cull, point-ellipsoid
// roots, broad phase, mid phase, and the whole update with the write-up's budget beside it.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "bench_suite.hpp"
#include "cull_scene.hpp"
#include "drive_report.hpp"
#include "drive_scene.hpp"
#include "midphase_scene.hpp"
#include "point_queries.hpp"
#include "support/ellipsoid_reference.hpp"
#include "tightest_turn_scene.hpp"
#include "tool_world_settings.hpp"
#include "trackphys/collision/brute_force_collider.hpp"
#include "trackphys/collision/static_world.hpp"
#include "trackphys/error.hpp"
#include "trackphys/geometry/point_ellipsoid.hpp"
#include "trackphys/world/autopilot.hpp"
#include "trackphys/world/world.hpp"

namespace trackphys::suite {

Spread spread(std::vector<double> sample) {
    if (sample.empty()) throw Error("bench: an empty sample has no spread");
    std::sort(sample.begin(), sample.end());
    const auto at = [&](double q) {
        return sample[static_cast<std::size_t>(q * double(sample.size() - 1))];
    };
    return {at(0.5), at(0.99), sample.back()};
}

double thread_cpu_ns() {
    timespec now{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
    return double(now.tv_sec) * 1e9 + double(now.tv_nsec);
}

std::vector<TimedDrive> drive_timed(const Track& track, const std::vector<Driver>& drivers,
                                    int updates) {
    std::vector<Autopilot> autopilots;
    for (const Driver& d : drivers) autopilots.emplace_back(track, d.car->spec());
    std::vector<TimedDrive> drives(drivers.size());
    constexpr int kBlock = 10;
    for (int first = 0; first < updates; first += kBlock)
        for (std::size_t i = 0; i < drivers.size(); ++i)
            for (int k = first; k < std::min(first + kBlock, updates); ++k) {
                Car& car = *drivers[i].car;
                car.set_inputs(autopilots[i].drive(car));
                const double start = thread_cpu_ns();
                drivers[i].update();
                drives[i].update_ns.push_back(thread_cpu_ns() - start);
                drives[i].positions.push_back(car.state().position);
            }
    for (std::size_t i = 0; i < drivers.size(); ++i)
        drives[i].final_speed_kmh = drivers[i].car->speed() * 3.6;
    return drives;
}

// Cull: one pass = the 320 bounding spheres of an update (40 sub-steps x 8 ellipsoids)
// against every broad-phase candidate of the tightest turn.
void bench_cull(BenchRun& run) {
    run.progress("cull", "tightest turn scene");
    const bench::CullScene scene(bench::tightest_turn_scene());
    const double tests = double(scene.tests());
    struct Variant {
        bench::CullVariant variant;
        const char* name;
        const char* note;
    };
    const Variant variants[] = {
        {bench::CullVariant::xyz_order, "x-y-z order, first-vertex origin",
         "the write-up's first cull"},
        {bench::CullVariant::normal_first, "normal first", "write-up: about half the cull time"},
        {bench::CullVariant::longest_edge_normal_first, "normal first + longest-edge origin",
         "write-up: a little more; ours"}};
    // In turns: each pass is ~0.1 ms and reads the same ~50 kB, so taking turns keeps every
    // variant's caches alike while a busy moment of the machine falls on all three.
    run.progress("cull", "the three variants in turns");
    std::vector<std::size_t> kept(std::size(variants), 0);
    std::vector<std::function<void()>> passes;
    for (std::size_t i = 0; i < std::size(variants); ++i)
        passes.push_back([&, i] { keep(kept[i] = bench::cull_pass(scene, variants[i].variant)); });
    const std::vector<double> medians = median_call_ns_in_turns(passes, 1, run.batches(21, 201));
    for (std::size_t i = 0; i < std::size(variants); ++i) {
        const Variant& v = variants[i];
        const double ns = medians[i];
        BenchRow& row = run.add("cull", v.name, ns,
                                v.variant == bench::CullVariant::xyz_order ? "" : variants[0].name);
        // A cull may keep too much, never too little: the pairs within reach by the
        // long-double distance that it dropped.
        const bench::CullCheck check = bench::check_cull(scene, v.variant);
        row.figures = {{"ns_per_test", ns / tests},
                       {"candidates", double(scene.longest_edge_origin.size())},
                       {"kept_pct", 100.0 * double(kept[i]) / tests},
                       {"touching", double(check.touching)},
                       {"missed", double(check.missed)}};
        row.note = check.missed ? "DROPS TOUCHING PAIRS" : v.note;
    }
}

// Point-ellipsoid roots: 4096 points of every class (tests/support's generator), each finder
// on all of them; error = |distance - the long-double reference's| (tests/support).
void bench_roots(BenchRun& run) {
    const std::vector<bench::PointQuery> queries = bench::point_queries(test::PointClass::count);
    run.progress("roots", "long-double references");
    std::vector<double> exact;
    for (const bench::PointQuery& q : queries)
        exact.push_back(double(
            test::ReferenceSolver<3>({q.radii.x, q.radii.y, q.radii.z}, {q.p.x, q.p.y, q.p.z})
                .closest()
                .offset));
    struct Finder {
        bench::RootFinder finder;
        const char* name;
        const char* note;
    };
    const Finder finders[] = {
        {bench::RootFinder::bisection, "bisection", "write-up's first solver: 15-16 iterations"},
        {bench::RootFinder::writeup_newton, "write-up Newton", "write-up: 5 Newton steps"},
        {bench::RootFinder::ours, "ours (concave-h Newton)", "exact; the library's"}};
    for (const Finder& f : finders) {
        run.progress("roots", f.name);
        std::size_t i = 0;
        const double ns = median_call_ns(
            [&] {
                keep(bench::closest_point(queries[i], f.finder));
                i = i + 1 == queries.size() ? 0 : i + 1;
            },
            int(queries.size()), run.batches(11, 51));
        double steps = 0.0, worst_steps = 0.0;
        std::vector<double> error;
        // Relative to the query's scale, the larger of its distance and its longest semi-axis:
        // the far class's points are up to 1e6 semi-axes out, where 1e-16 of the distance is
        // already 1e-10 m.
        double worst_relative = 0.0;
        std::size_t not_finite = 0;
        for (std::size_t k = 0; k < queries.size(); ++k) {
            const PointEllipsoid r = bench::closest_point(queries[k], f.finder);
            steps += r.iterations;
            worst_steps = std::max(worst_steps, double(r.iterations));
            if (!std::isfinite(r.distance)) {
                ++not_finite;
                continue;
            }
            error.push_back(std::abs(r.distance - exact[k]));
            worst_relative = std::max(
                worst_relative, error.back() / std::max(std::abs(exact[k]), queries[k].radii.x));
        }
        const Spread e = spread(error);
        BenchRow& row = run.add("roots", f.name, ns,
                                f.finder == bench::RootFinder::bisection ? "" : finders[0].name);
        row.figures = {{"steps_mean", steps / double(queries.size())},
                       {"steps_max", worst_steps},
                       {"err_median_m", e.median},
                       {"err_max_m", e.max},
                       {"err_max_relative", worst_relative},
                       {"not_finite", double(not_finite)}};
        row.note = f.note;
    }
}

// Broad phase: the tightest turn's update box (the car's box swept over 10 ms at 1000 km/h,
// padded) against the default track: brute force over every triangle, the write-up's first
// version (every triangle of each collider whose box meets the car's), and our BVHs.
void bench_broad_phase(BenchRun& run) {
    run.progress("broad", "building colliders");
    const bench::TightestTurnScene& turn = bench::tightest_turn_scene();
    const Aabb& box = turn.update_box;
    const BruteForceCollider everything(bench::merged_track_mesh(turn.track));
    std::vector<BruteForceCollider> chunks;
    StaticWorld world;
    for (const TrackChunk& chunk : turn.track.chunks) {
        chunks.emplace_back(chunk.mesh);
        world.add(std::make_shared<const StaticCollider>(chunk.mesh));
    }
    std::vector<std::uint32_t> found;
    std::vector<TriangleRef> refs;
    const auto brute_all = [&] {
        found.clear();
        everything.query_aabb(box, found);
        keep(found.data());
    };
    const auto brute_colliders = [&] {
        found.clear();
        for (std::size_t c = 0; c < chunks.size(); ++c)
            if (turn.track.chunks[c].bounds.overlaps(box)) chunks[c].query_aabb(box, found);
        keep(found.data());
    };
    const auto bvh = [&] {
        refs.clear();
        world.query_aabb(box, refs);
        keep(refs.data());
    };
    run.progress("broad", "brute force");
    const double all_ns = median_call_ns(brute_all, 1, run.batches(11, 101));
    const std::size_t all_found = found.size();
    const double colliders_ns = median_call_ns(brute_colliders, 1, run.batches(21, 201));
    const std::size_t colliders_found = found.size();
    run.progress("broad", "BVH");
    const double bvh_ns = median_call_ns(bvh, 10, run.batches(21, 201));
    const double triangles = double(everything.triangle_count());
    // The three sets, untimed, as indices into the merged mesh (its chunks in order).
    std::vector<std::uint32_t> first_of_chunk;
    std::uint32_t merged = 0;
    for (const TrackChunk& chunk : turn.track.chunks) {
        first_of_chunk.push_back(merged);
        merged += static_cast<std::uint32_t>(chunk.mesh.triangles.size());
    }
    std::vector<std::uint32_t> all_set, colliders_set, bvh_set;
    everything.query_aabb(box, all_set);
    for (std::size_t c = 0; c < chunks.size(); ++c) {
        if (!turn.track.chunks[c].bounds.overlaps(box)) continue;
        found.clear();
        chunks[c].query_aabb(box, found);
        for (const std::uint32_t t : found) colliders_set.push_back(first_of_chunk[c] + t);
    }
    for (const TriangleRef& ref : refs)
        bvh_set.push_back(first_of_chunk[ref.collider] + ref.triangle);
    for (std::vector<std::uint32_t>* set : {&all_set, &colliders_set, &bvh_set})
        std::sort(set->begin(), set->end());
    const bool same_sets = all_set == colliders_set && all_set == bvh_set;
    run.add("broad", "brute force, every triangle", all_ns).figures = {
        {"candidates", double(all_found)}, {"triangles", triangles}};
    BenchRow& first = run.add("broad", "brute force in hit colliders", colliders_ns,
                              "brute force, every triangle");
    first.figures = {{"candidates", double(colliders_found)}};
    first.note = "the write-up's first: ~2 ms";
    BenchRow& ours =
        run.add("broad", "BVH per collider (ours)", bvh_ns, "brute force, every triangle");
    ours.figures = {{"candidates", double(refs.size())},
                    {"x_faster_than_hit_colliders", colliders_ns / bvh_ns}};
    ours.note = same_sets ? "write-up: under 400 us; same sets" : "TRIANGLE SETS DIFFER";
}

// Mid phase: one update's mid-phase work (begin_update and each step's list per ellipsoid,
// as World does) per variant, and with the write-up's bounding-sphere cull over the lists it
// hands out every sub-step (40 x 8 culls), the same cull for every variant so that the ratio
// compares the lists; the write-up's per-update tree queried every step is the reference.
// World's own cull (the extent test: dearer per triangle, fewer survivors for the exact
// phase, which this group does not run) is timed beside it over ours' lists. The target
// holds only if ours' lists hold every triangle that touches an ellipsoid, as many as the
// whole broad-phase list ("none") does: a list that drops one is fast and wrong.
void bench_mid_phase(BenchRun& run) {
    run.progress("mid", "colliders and precomputed plane trees");
    const bench::MidScene& scene = bench::mid_scene();
    const std::vector<bench::MidVariant>& variants = bench::mid_variants();
    const std::string reference = variants[bench::kWriteupVariant].name;
    bench::UpdateLists lists;
    double writeup_with_cull_ns = 0.0;
    std::vector<bench::ListEntry> touching_in_everything;  // in one update's "none" lists
    for (std::size_t v = 0; v < variants.size(); ++v) {
        const bench::MidVariant& variant = variants[v];
        run.progress("mid", variant.name);
        const std::unique_ptr<MidPhase> mid = bench::make_mid_phase(variant.mode);
        const std::vector<bench::ListEntry> touching =
            bench::touching_in_lists(*mid, variant, lists);
        if (variant.mode == MidPhaseMode::none) touching_in_everything = touching;
        std::size_t total = 0, kept = 0;
        const auto timed = [&](bench::SubstepCull cull) {
            return median_call_ns(
                [&] {
                    total = bench::run_update(*mid, variant, cull, lists, kept);
                    keep(kept);
                },
                1, run.batches(21, 201));
        };
        const double with_cull_ns = timed(bench::SubstepCull::bounding_sphere);
        mid->reset_counters();
        const double ns = timed(bench::SubstepCull::none);
        const double updates = double(mid->counters().updates);
        BenchRow& row =
            run.add("mid", variant.name, ns, v == bench::kWriteupVariant ? "" : reference);
        row.figures = {{"tested_per_ellipsoid_substep", bench::tested_per_ellipsoid_substep(total)},
                       {"queries_per_update", double(mid->counters().queries) / updates},
                       {"with_cull_us", with_cull_ns * 1e-3}};
        if (variant.mode == MidPhaseMode::precomputed_tree)
            row.figures.push_back({"trees_build_ms_all_colliders", scene.trees_build_ms});
        row.note = variant.note;
        if (v == bench::kWriteupVariant) writeup_with_cull_ns = with_cull_ns;
        if (v == bench::kDefaultVariant) {
            // The target counts the cull: a list that looks further ahead costs fewer queries
            // but more sub-step tests, so the mid phase alone would flatter it.
            const BenchRow& writeup = run.row("mid", reference);
            const double with_world_cull_ns = timed(bench::SubstepCull::world_extent);
            // What each cull leaves the exact phase in one update.
            std::size_t kept_by_sphere = 0, kept_by_extent = 0;
            bench::run_update(*mid, variant, bench::SubstepCull::bounding_sphere, lists,
                              kept_by_sphere);
            bench::run_update(*mid, variant, bench::SubstepCull::world_extent, lists,
                              kept_by_extent);
            char evidence[256];
            std::snprintf(
                evidence, sizeof evidence,
                "with the sub-step cull (spheres): write-up %.3g us, ours %.3g us (%zu kept); "
                "ours with World's extent cull %.3g us (%zu kept); mid phase alone "
                "%.3gx; %zu touching, none's %zu",
                writeup_with_cull_ns * 1e-3, with_cull_ns * 1e-3, kept_by_sphere,
                with_world_cull_ns * 1e-3, kept_by_extent, writeup.median_ns / ns, touching.size(),
                touching_in_everything.size());
            const bool holds_every_touching =
                std::includes(touching.begin(), touching.end(), touching_in_everything.begin(),
                              touching_in_everything.end());
            run.add_target(
                "mid phase + sub-step cull per update: write-up's per-update tree / ours",
                writeup_with_cull_ns / with_cull_ns, 10.0, holds_every_touching, evidence);
            row.figures.push_back({"writeup_with_cull_x", writeup_with_cull_ns / with_cull_ns});
            row.figures.push_back({"with_world_cull_us", with_world_cull_ns * 1e-3});
        }
    }
}

// The whole update of one car (default car, default track seed 7, autopilot from the start) in each
// mid-phase mode, queried every step or looking ahead, World's profile off (and the default mode
// with it on, the cost of the per-phase clock reads, and with a surface table of ones, the cost
// of reading each wheel's surface: the same drive, bit for bit), the cars taking turns by
// blocks; the write-up's budget is the reference row.
void bench_update(BenchRun& run) {
    run.progress("update", "default track");
    const cli::DriveScene scene = cli::make_track_scene(kDemoTrackSeed);
    const CarSpec spec = CarSpec::default_car();
    const int updates = run.quick() ? 300 : 2000;
    BenchRow& budget = run.add("update", "write-up budget", cli::kWriteupTypicalUs * 1e3);
    budget.figures = {{"spikes_us", cli::kWriteupSpikeUs}};
    budget.note = "one car, 10 steps x 4 sub-steps x 8 ellipsoids";
    struct Combination {
        MidPhaseMode mode;
        int look_ahead;
        bool profile;
        const char* name;
        bool surface_table = false;
    };
    const int look_ahead = WorldSettings{}.mid_phase_look_ahead;
    const Combination combinations[] = {
        {MidPhaseMode::none, 1, false, "mid phase none"},
        {MidPhaseMode::per_update_tree, 1, false, "per-update PCA tree, every step (write-up)"},
        {MidPhaseMode::precomputed_tree, 1, false, "precomputed trees, every step"},
        {MidPhaseMode::precomputed_tree, look_ahead, false,
         "precomputed trees, looking ahead (default)"},
        {MidPhaseMode::precomputed_tree, look_ahead, true, "default, profile on"},
        {MidPhaseMode::precomputed_tree, look_ahead, false, "default, surface table (road, walls)",
         true}};
    run.progress("update", "worlds and precomputed trees");
    std::vector<std::unique_ptr<World>> worlds;
    std::vector<Driver> drivers;
    std::vector<std::uint64_t> tested(std::size(combinations), 0),
        substeps(std::size(combinations), 0);
    for (const Combination& c : combinations) {
        WorldSettings settings = cli::tool_world_settings();
        settings.mid_phase = c.mode;
        settings.mid_phase_look_ahead = c.look_ahead;
        settings.profile = c.profile;
        if (c.surface_table) settings.surfaces = {Surface{1.0}, Surface{1.0}};
        // The precomputed worlds share one set of trees.
        ColliderPlaneTrees trees;
        for (const auto& w : worlds)
            if (!w->plane_trees().empty()) trees = w->plane_trees();
        worlds.push_back(std::make_unique<World>(scene.statics, settings, trees));
        World& world = *worlds.back();
        world.add_car(spec, cli::start_on_track(*scene.track, spec));
        const std::size_t i = drivers.size();
        drivers.push_back({&world.car(0), [&world, &tested, &substeps, i] {
                               world.update();
                               tested[i] += world.last_profile().culled_tests;
                               substeps[i] += world.last_profile().ellipsoid_substeps;
                           }});
    }
    run.progress("update", "driving " + std::to_string(updates) + " updates in each combination");
    const std::vector<TimedDrive> drives = drive_timed(*scene.track, drivers, updates);
    for (std::size_t i = 0; i < drives.size(); ++i) {
        const Spread us = spread(drives[i].update_ns);
        BenchRow& row = run.add("update", combinations[i].name, us.median, "write-up budget");
        row.figures = {{"p99_us", us.p99 * 1e-3},
                       {"max_us", us.max * 1e-3},
                       {"tested_per_ellipsoid_substep", double(tested[i]) / double(substeps[i])},
                       {"updates", double(updates)},
                       {"final_kmh", drives[i].final_speed_kmh}};
        row.note = us.max <= cli::kWriteupSpikeUs * 1e3 ? "max within the 8 ms spike budget"
                                                        : "max over the 8 ms spike budget";
    }
}

}  // namespace trackphys::suite
