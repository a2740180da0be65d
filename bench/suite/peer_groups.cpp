// The peers, each optional (TRACKPHYS_HAVE_BULLET, TRACKPHYS_HAVE_FCL, TRACKPHYS_HAVE_MUJOCO:
// set by CMake when libbullet-dev / libfcl-dev / libmujoco-dev are found): ellipsoid-triangle
// contact against Bullet's GJK/EPA and FCL, mesh box queries against Bullet's quantized BVH,
// and the whole update with Bullet doing the collision work (the ellipsoid pair's peers are
// pair_group.cpp's). The cases, adapters and checks are bench/peers' own.
//
// Bullet is linked in its float build (libBulletCollision, what most users get): its double
// build has the same symbol names, so it cannot share this process; the bench_peers_*_double
// programs measure it.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "bench_suite.hpp"
#include "drive_scene.hpp"
#include "tightest_turn_scene.hpp"
#include "trackphys/world/world.hpp"

#if TRACKPHYS_HAVE_BULLET
#include "peers/bullet_car_loop.hpp"
#include "peers/bullet_contact.hpp"
#include "peers/mesh_peer_harness.hpp"
#endif
#if TRACKPHYS_HAVE_FCL
#include <fcl/config.h>

#include "peers/fcl_contact.hpp"
#endif
#if TRACKPHYS_HAVE_BULLET || TRACKPHYS_HAVE_FCL
#include "peers/contact_peer_harness.hpp"
#include "tool_world_settings.hpp"
#endif
#if TRACKPHYS_HAVE_MUJOCO
#include <mujoco/mujoco.h>
#endif

namespace trackphys::suite {

void not_built(BenchRun& run, const std::string& group, const std::string& peer) {
    const std::string why = "not built (install the peer's -dev package and reconfigure)";
    run.add(group, peer, 0.0).note = why;
    // A comparison that did not run is not met: a full run without a peer exits 3.
    run.add_target(group + ": against " + peer, 0.0, 1.0, false, why);
}

std::vector<PeerStatus> peer_status() {
    std::vector<PeerStatus> peers;
#if TRACKPHYS_HAVE_BULLET
    peers.push_back({"bullet",
                     "Bullet " + std::to_string(BT_BULLET_VERSION / 100) + "." +
                         std::to_string(BT_BULLET_VERSION % 100),
                     true,
                     std::string(peers::bullet_precision()) +
                         " btScalar; double: bench_peers_*_bullet_double"});
#else
    peers.push_back({"bullet", "Bullet", false, "install libbullet-dev and reconfigure"});
#endif
#if TRACKPHYS_HAVE_FCL
    peers.push_back({"fcl", std::string("FCL ") + FCL_VERSION, true, "libccd and its own GJK"});
#else
    peers.push_back({"fcl", "FCL", false, "install libfcl-dev and reconfigure"});
#endif
#if TRACKPHYS_HAVE_MUJOCO
    peers.push_back({"mujoco",
                     "MuJoCo " + std::to_string(mjVERSION_HEADER / 100) + "." +
                         std::to_string(mjVERSION_HEADER / 10 % 10) + "." +
                         std::to_string(mjVERSION_HEADER % 10),
                     true, "its convex collider (libccd MPR), ellipsoid pairs only"});
#else
    peers.push_back({"mujoco", "MuJoCo", false, "install libmujoco-dev and reconfigure"});
#endif
    return peers;
}

// Ellipsoid-triangle contact: the peer harness's case sets (20k hard mix, 5k shallow road;
// 400 and 200 with --quick), each method timed per case (8 calls back to back), depth error
// against the long-double reference.
void bench_contact_peers(BenchRun& run) {
#if TRACKPHYS_HAVE_BULLET || TRACKPHYS_HAVE_FCL
    std::vector<peers::Peer> methods;
#if TRACKPHYS_HAVE_BULLET
    methods.push_back(peers::bullet_contact_peer(std::string("Bullet GJK/EPA (") +
                                                 peers::bullet_precision() + ")"));
#else
    not_built(run, "contact", "Bullet GJK/EPA");
#endif
#if TRACKPHYS_HAVE_FCL
    for (peers::Peer& p : peers::fcl_contact_peers()) methods.push_back(std::move(p));
#else
    not_built(run, "contact", "FCL");
#endif
    run.progress("contact", "cases and long-double references");
    const std::vector<peers::CaseSet> sets =
        peers::make_case_sets(run.quick() ? 400 : 20000, run.quick() ? 200 : 5000);
    double slowest_speedup = 1e300, least_accuracy = 1e300;
    std::string slowest, least;
    // The targets' correctness: ours holds its depth contract on every set (the targets' own
    // cases are the hard mix's), and what each peer failed on the hard mix.
    constexpr double kDepthContract = 1e-9;  // m
    bool ours_holds = true;
    std::string evidence, broken;
    for (const peers::CaseSet& set : sets) {
        run.progress("contact", set.name + ": ours");
        const peers::MethodResult ours = peers::measure_ours(set);
        const std::string ours_name = set.name + ": trackphys";
        const auto add = [&](const std::string& name, const peers::MethodResult& r,
                             const std::string& versus) {
            BenchRow& row = run.add("contact", name, r.median_ns, versus);
            row.figures = {{"cases", double(r.cases)},
                           {"mean_ns", r.mean_ns},
                           {"err_median_m", r.error_median},
                           {"err_p99_m", r.error_p99},
                           {"err_max_m", r.error_max},
                           {"touch_disagreements", double(r.touch_disagreements)},
                           {"failures", double(r.failures)}};
        };
        add(ours_name, ours, "");
        if (!(ours.error_max <= kDepthContract && ours.failures == 0)) {
            ours_holds = false;
            broken += (broken.empty() ? "; ours BROKE the contract on " : ", ") + set.name;
        }
        if (set.name == "hard_mix") {
            char text[96];
            std::snprintf(text, sizeof text,
                          "ours: err_max %.2g m, %zu failures in %zu cases; peers' failures:",
                          ours.error_max, ours.failures, ours.cases);
            evidence = text;
        }
        for (const peers::Peer& peer : methods) {
            run.progress("contact", set.name + ": " + peer.name);
            const peers::MethodResult r = peers::measure(peer.name, set, peer.prepare(set));
            add(set.name + ": " + peer.name, r, ours_name);
            // The targets are on the 20k hard-mix cases. Our errors are ~1e-16 m or
            // exactly 0: a floor of 1e-15 m keeps the ratio finite.
            if (set.name != "hard_mix") continue;
            evidence += (evidence.back() == ':' ? " " : ", ") + peer.name + " " +
                        std::to_string(r.failures);
            const double speedup = r.median_ns / ours.median_ns;
            const double accuracy = r.error_max / std::max(ours.error_max, 1e-15);
            if (speedup < slowest_speedup) slowest_speedup = speedup, slowest = peer.name;
            if (accuracy < least_accuracy) least_accuracy = accuracy, least = peer.name;
        }
    }
    evidence += broken;
    if (!methods.empty()) {
        run.add_target("contact, hard mix: fastest peer's time / ours (" + slowest + ")",
                       slowest_speedup, 10.0, ours_holds, evidence);
        run.add_target("contact, hard mix: most accurate peer's max error / ours (" + least + ")",
                       least_accuracy, 100.0, ours_holds, evidence);
    }
#else
    not_built(run, "contact", "Bullet GJK/EPA");
    not_built(run, "contact", "FCL");
#endif
}

// Mesh box queries: the default track as one mesh (and in the full run bench_collision_bvh's
// 300k-triangle banked loop), random and driving padded car boxes (10k each, 500 --quick).
void bench_mesh_peers(BenchRun& run) {
#if TRACKPHYS_HAVE_BULLET
    const std::size_t boxes = run.quick() ? 500 : 10000;
    std::vector<peers::SceneResult> results;
    run.progress("mesh", "default track");
    peers::run_scene(peers::track_scene(boxes), results);
    if (!run.quick()) {
        run.progress("mesh", "300k-triangle banked loop");
        peers::run_scene(peers::loop_scene(boxes), results);
    }
    double least = 1e300;
    std::string where;
    std::size_t differ = 0;
    for (const peers::SceneResult& r : results) {
        const std::string ours_name = r.scene + ": trackphys BVH";
        BenchRow& ours = run.add("mesh", ours_name, r.ours_us * 1e3);
        ours.figures = {{"triangles", double(r.triangles)},
                        {"build_ms", r.ours_build_ms},
                        {"bytes_per_tri", r.ours_bytes_per_tri},
                        {"found_mean", r.ours_found_mean}};
        BenchRow& nodes =
            run.add("mesh", r.scene + ": Bullet quantized BVH", r.bullet_nodes_us * 1e3, ours_name);
        nodes.figures = {{"build_ms", r.bullet_build_ms},
                         {"node_bytes_per_tri", r.bullet_node_bytes_per_tri},
                         {"all_bytes_per_tri", r.bullet_total_bytes_per_tri},
                         {"found_mean", r.bullet_found_mean},
                         {"extras", double(r.extras)},
                         {"missing", double(r.missing + r.ours_missed)}};
        const bool same_sets = r.missing + r.ours_missed == 0 && r.extra_gap_max <= r.slack;
        nodes.note = same_sets ? "superset: extras within quantisation" : "TRIANGLE SETS DIFFER";
        differ += same_sets ? 0 : 1;
        run.add("mesh", r.scene + ": Bullet exact set", r.bullet_exact_us * 1e3, ours_name).note =
            "processAllTriangles + our box test on its triangles (the set not compared)";
        if (r.bullet_nodes_us / r.ours_us < least)
            least = r.bullet_nodes_us / r.ours_us, where = r.scene;
    }
    run.add_target("mesh query: Bullet nodes / ours (" + where + ")", least, 3.0, differ == 0,
                   differ == 0 ? "triangle sets match in every scene"
                               : "TRIANGLE SETS DIFFER in " + std::to_string(differ) + " of " +
                                     std::to_string(results.size()) + " scenes");
#else
    not_built(run, "mesh", "Bullet btBvhTriangleMeshShape");
#endif
}

// The whole update with Bullet's GJK/EPA as the narrow phase: the same car
// (CarSpec::default_car) from the default track's start line, driven by autopilot, by
// World::update (ours), by peers::BulletNarrowPhaseLoop (our BVH and mid phase, GJK/EPA per
// mid-phase candidate: the narrow phases alone compared) and by peers::BulletCarLoop (Bullet's
// BVH, GJK/EPA per broad-phase candidate: Bullet's own way), taking turns; us per update and
// how far each Bullet car drifts from ours.
void bench_update_peers(BenchRun& run) {
#if TRACKPHYS_HAVE_BULLET
    run.progress("bullet update", "default track");
    const cli::DriveScene scene = cli::make_track_scene(kDemoTrackSeed);
    const CarSpec spec = CarSpec::default_car();
    const int updates = run.quick() ? 100 : 500;
    WorldSettings settings = cli::tool_world_settings();
    settings.profile = false;
    World world(scene.statics, settings);
    world.add_car(spec, cli::start_on_track(*scene.track, spec));
    peers::BulletNarrowPhaseLoop narrow(scene.statics, settings, world.plane_trees());
    Car narrow_car(spec, cli::start_on_track(*scene.track, spec));
    run.progress("bullet update", "Bullet's BVH");
    peers::BulletCarLoop bullet(bench::merged_track_mesh(*scene.track), settings);
    Car bullet_car(spec, cli::start_on_track(*scene.track, spec));
    run.progress("bullet update", "driving " + std::to_string(updates) + " updates each");
    const std::vector<TimedDrive> drives =
        drive_timed(*scene.track,
                    {{&world.car(0), [&] { world.update(); }},
                     {&narrow_car, [&] { narrow.update(narrow_car); }},
                     {&bullet_car, [&] { bullet.update(bullet_car); }}},
                    updates);
    const TimedDrive& ours = drives[0];
    const Spread us = spread(ours.update_ns);
    const std::string ours_name = "World::update (ours)";
    BenchRow& row = run.add("bullet update", ours_name, us.median);
    row.figures = {{"p99_us", us.p99 * 1e-3},
                   {"updates", double(updates)},
                   {"final_kmh", ours.final_speed_kmh}};

    struct Drift {
        double after_10 = 0.0, after_all = 0.0, max = 0.0;
    };
    const auto add_peer = [&](const TimedDrive& theirs, const peers::GjkEpaCounts& counts,
                              const std::string& name, const char* note) {
        const auto drift_after = [&](std::size_t n) {
            return glm::length(ours.positions[n - 1] - theirs.positions[n - 1]);
        };
        Drift drift{drift_after(std::min<std::size_t>(10, updates)),
                    drift_after(std::size_t(updates)), 0.0};
        for (std::size_t n = 1; n <= ours.positions.size(); ++n)
            drift.max = std::max(drift.max, drift_after(n));
        const Spread them = spread(theirs.update_ns);
        BenchRow& peer = run.add("bullet update", name, them.median, ours_name);
        peer.figures = {{"p99_us", them.p99 * 1e-3},
                        {"pair_tests_per_update", double(counts.pair_tests) / updates},
                        {"failures", double(counts.failures)},
                        {"drift_m_after_10", drift.after_10},
                        {"drift_m_after_all", drift.after_all},
                        {"drift_m_max", drift.max},
                        {"final_kmh", theirs.final_speed_kmh}};
        peer.note = note;
        return drift;
    };
    const std::string precision = std::string(" (") + peers::bullet_precision() + ")";
    add_peer(drives[1], narrow.counts(),
             "our BVH + mid phase, GJK/EPA per mid-phase candidate" + precision,
             "the narrow phases alone: our lists, Bullet's GJK/EPA on every listed triangle");
    const Drift drift =
        add_peer(drives[2], bullet.counts(), "GJK/EPA per broad-phase candidate" + precision,
                 "Bullet's BVH per ellipsoid per sub-step, GJK/EPA on every triangle it reports");
    char evidence[200];
    std::snprintf(evidence, sizeof evidence,
                  "drift from ours %.3g m after 10 updates, %.3g m after %d (max %.3g m); Bullet "
                  "failures %zu of %zu GJK/EPA",
                  drift.after_10, drift.after_all, updates, drift.max, bullet.counts().failures,
                  bullet.counts().pair_tests);
    // The same drive, as far as two narrow phases can agree: the cars start alike (float
    // GJK/EPA's errors grow into metres over hundreds of updates, as any two integrators'
    // would) and Bullet's failures stay rare, or its loop did less than ours.
    const bool same_drive = drift.after_10 <= 0.01 && double(bullet.counts().failures) <=
                                                          1e-3 * double(bullet.counts().pair_tests);
    run.add_target("whole update: GJK/EPA per broad-phase candidate / ours",
                   spread(drives[2].update_ns).median / us.median, 20.0, same_drive, evidence);
#else
    not_built(run, "bullet update", "GJK/EPA per broad-phase candidate");
#endif
}

}  // namespace trackphys::suite
