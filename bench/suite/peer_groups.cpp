// The peers, each optional (TRACKPHYS_HAVE_BULLET, TRACKPHYS_HAVE_FCL: set by CMake when
// libbullet-dev / libfcl-dev are found): ellipsoid-triangle contact against Bullet's GJK/EPA
// and FCL, mesh box queries against Bullet's quantized BVH, and the whole update with Bullet
// doing the collision work. The cases, adapters and checks are bench/peers' own.
//
// Bullet is linked in its float build (libBulletCollision, what most users get): its double
// build has the same symbol names, so it cannot share this process; the bench_peers_*_double
// programs measure it.

#include <algorithm>
#include <cmath>
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
#endif

namespace trackphys::suite {
namespace {

[[maybe_unused]] void not_built(BenchRun& run, const std::string& group, const std::string& peer) {
    run.add(group, peer, 0.0).note = "not built (install the peer's -dev package and reconfigure)";
}

}  // namespace

std::vector<PeerStatus> peer_status() {
    std::vector<PeerStatus> peers;
#if TRACKPHYS_HAVE_BULLET
    peers.push_back({"bullet", "Bullet " + std::to_string(BT_BULLET_VERSION / 100) + "." +
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
    return peers;
}

// Ellipsoid-triangle contact: the peer harness's case sets (20k hard mix, 5k shallow road;
// 400 and 200 with --quick), each method timed per case (8 calls back to back), depth error
// against the long-double reference.
void bench_contact_peers(BenchRun& run) {
#if TRACKPHYS_HAVE_BULLET || TRACKPHYS_HAVE_FCL
    std::vector<peers::Peer> methods;
#if TRACKPHYS_HAVE_BULLET
    methods.push_back(peers::bullet_contact_peer(std::string("Bullet GJK/EPA (") + peers::bullet_precision() + ")"));
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
    for (const peers::CaseSet& set : sets) {
        run.progress("contact", set.name + ": ours");
        const peers::MethodResult ours = peers::measure_ours(set);
        const std::string ours_name = set.name + ": trackphys";
        const auto add = [&](const std::string& name, const peers::MethodResult& r, const std::string& versus) {
            BenchRow& row = run.add("contact", name, r.median_ns, versus);
            row.figures = {{"cases", double(r.cases)},
                           {"err_median_m", r.error_median},
                           {"err_p99_m", r.error_p99},
                           {"err_max_m", r.error_max},
                           {"touch_disagreements", double(r.touch_disagreements)},
                           {"failures", double(r.failures)}};
        };
        add(ours_name, ours, "");
        for (const peers::Peer& peer : methods) {
            run.progress("contact", set.name + ": " + peer.name);
            const peers::MethodResult r = peers::measure(peer.name, set, peer.prepare(set));
            add(set.name + ": " + peer.name, r, ours_name);
            // The targets are on the 20k hard-mix cases. Our errors are ~1e-16 m or
            // exactly 0: a floor of 1e-15 m keeps the ratio finite.
            if (set.name != "hard_mix") continue;
            const double speedup = r.median_ns / ours.median_ns;
            const double accuracy = r.error_max / std::max(ours.error_max, 1e-15);
            if (speedup < slowest_speedup) slowest_speedup = speedup, slowest = peer.name;
            if (accuracy < least_accuracy) least_accuracy = accuracy, least = peer.name;
        }
    }
    if (!methods.empty()) {
        run.add_target("contact, hard mix: fastest peer's time / ours (" + slowest + ")", slowest_speedup, 10.0);
        run.add_target("contact, hard mix: most accurate peer's max error / ours (" + least + ")", least_accuracy,
                       100.0);
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
    for (const peers::SceneResult& r : results) {
        const std::string ours_name = r.scene + ": trackphys BVH";
        BenchRow& ours = run.add("mesh", ours_name, r.ours_us * 1e3);
        ours.figures = {{"triangles", double(r.triangles)},
                        {"build_ms", r.ours_build_ms},
                        {"bytes_per_tri", r.ours_bytes_per_tri},
                        {"found_mean", r.ours_found_mean}};
        BenchRow& nodes = run.add("mesh", r.scene + ": Bullet quantized BVH", r.bullet_nodes_us * 1e3, ours_name);
        nodes.figures = {{"build_ms", r.bullet_build_ms},
                         {"node_bytes_per_tri", r.bullet_node_bytes_per_tri},
                         {"all_bytes_per_tri", r.bullet_total_bytes_per_tri},
                         {"found_mean", r.bullet_found_mean},
                         {"extras", double(r.extras)},
                         {"missing", double(r.missing + r.ours_missed)}};
        nodes.note = r.missing + r.ours_missed == 0 && r.extra_gap_max <= r.slack
                         ? "superset: extras within quantisation"
                         : "TRIANGLE SETS DIFFER";
        run.add("mesh", r.scene + ": Bullet exact set", r.bullet_exact_us * 1e3, ours_name).note =
            "processAllTriangles + box filter: ours' set";
        if (r.bullet_nodes_us / r.ours_us < least) least = r.bullet_nodes_us / r.ours_us, where = r.scene;
    }
    run.add_target("mesh query: Bullet nodes / ours (" + where + ")", least, 3.0);
#else
    not_built(run, "mesh", "Bullet btBvhTriangleMeshShape");
#endif
}

// The whole update with Bullet's collision: the same car (CarSpec::default_car) from the
// default track's start line, driven by autopilot, by World::update (ours) and by
// peers::BulletCarLoop taking turns; us per update and how far the two trajectories drift apart.
void bench_update_peers(BenchRun& run) {
#if TRACKPHYS_HAVE_BULLET
    run.progress("bullet update", "default track");
    const cli::DriveScene scene = cli::make_track_scene(7);
    const CarSpec spec = CarSpec::default_car();
    const int updates = run.quick() ? 100 : 500;
    WorldSettings settings;
    settings.profile = false;
    World world(scene.statics, settings);
    world.add_car(spec, cli::start_on_track(*scene.track, spec));
    run.progress("bullet update", "Bullet's BVH");
    peers::BulletCarLoop bullet(bench::merged_track_mesh(*scene.track), settings);
    Car car(spec, cli::start_on_track(*scene.track, spec));
    run.progress("bullet update", "driving " + std::to_string(updates) + " updates each");
    const std::vector<TimedDrive> drives = drive_timed(
        *scene.track, {{&world.car(0), [&] { world.update(); }}, {&car, [&] { bullet.update(car); }}}, updates);
    const TimedDrive& ours = drives[0];
    const TimedDrive& theirs = drives[1];

    const auto drift_after = [&](std::size_t n) {
        return glm::length(ours.positions[n - 1] - theirs.positions[n - 1]);
    };
    double drift_max = 0.0;
    for (std::size_t n = 1; n <= ours.positions.size(); ++n) drift_max = std::max(drift_max, drift_after(n));
    const Spread us = spread(ours.update_ns), them = spread(theirs.update_ns);
    BenchRow& row = run.add("bullet update", "World::update (ours)", us.median);
    row.figures = {{"p99_us", us.p99 * 1e-3}, {"updates", double(updates)}, {"final_kmh", ours.final_speed_kmh}};
    BenchRow& peer = run.add("bullet update", std::string("Bullet BVH + GJK/EPA (") + peers::bullet_precision() + ")",
                             them.median, "World::update (ours)");
    peer.figures = {{"p99_us", them.p99 * 1e-3},
                    {"pair_tests_per_update", double(bullet.pair_tests()) / updates},
                    {"failures", double(bullet.failures())},
                    {"drift_m_after_10", drift_after(std::min<std::size_t>(10, updates))},
                    {"drift_m_after_all", drift_after(std::size_t(updates))},
                    {"drift_m_max", drift_max},
                    {"final_kmh", theirs.final_speed_kmh}};
    peer.note = "same Car, loop and autopilot; Bullet's BVH per ellipsoid per sub-step";
    run.add_target("whole update: Bullet collision / ours", them.median / us.median, 20.0);
#else
    not_built(run, "bullet update", "Bullet BVH + GJK/EPA");
#endif
}

}  // namespace trackphys::suite
