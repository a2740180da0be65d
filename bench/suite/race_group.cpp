// The race group: a field of cars on the default track (RaceDrivers, as `trackphys race`),
// 1 to 128 cars on 1 and 2 threads, the cost of a pair of cars that do not touch, and
// issue 16's targets. A field's 1- and 2-thread races run side by side, timed in
// alternating chunks of updates, so that the threads' ratio and the 1-thread CPU time per
// car-update see the same phases of a shared host's speed.

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "bench_suite.hpp"
#include "drive_scene.hpp"
#include "trackphys/collision/mid_phase.hpp"
#include "trackphys/world/race_drivers.hpp"
#include "trackphys/world/race_grid.hpp"
#include "trackphys/world/world.hpp"

namespace trackphys::suite {
namespace {

struct RaceTiming {
    Spread update_ns;          // wall clock
    double mean_ns = 0.0;      // wall clock
    double cpu_mean_ns = 0.0;  // this thread's CPU time: the whole update on one thread
    std::uint64_t state_hash = 0;
    std::uint64_t resets = 0;   // the reset policy's, over the field
    std::uint64_t rescues = 0;  // cars put back on the road by RaceDrivers
};

double mean(const std::vector<double>& x) {
    double sum = 0.0;
    for (const double v : x) sum += v;
    return sum / static_cast<double>(x.size());
}

// The race of `cars` cars from the grid on `threads` threads, per timed update the wall
// clock and this thread's CPU time. Its updates run in chunks between those of another race
// (interleaved_races), so it keeps its world between them.
class TimedRace {
  public:
    TimedRace(const cli::DriveScene& scene, const ColliderPlaneTrees& trees, std::size_t cars,
              int threads, int timed_updates)
        : world_(scene.statics, settings(threads), trees),
          drivers_(*scene.track, CarSpec::default_car(), cars) {
        drivers_.add_cars(world_);
        ns_.reserve(static_cast<std::size_t>(timed_updates));
        cpu_ns_.reserve(static_cast<std::size_t>(timed_updates));
    }

    // The next `updates` updates, timed or not (the warm-up: the field spreads out and every
    // buffer reaches its size).
    void run(int updates, bool timed) {
        for (int u = 0; u < updates; ++u) {
            drivers_.drive(world_);
            const double cpu_start = thread_cpu_ns();
            const auto start = std::chrono::steady_clock::now();
            world_.update();
            const auto end = std::chrono::steady_clock::now();
            const double cpu_end = thread_cpu_ns();
            drivers_.after_update(world_);
            if (!timed) continue;
            ns_.push_back(std::chrono::duration<double, std::nano>(end - start).count());
            cpu_ns_.push_back(cpu_end - cpu_start);
        }
    }

    RaceTiming timing() const {
        RaceTiming timing;
        timing.mean_ns = mean(ns_);
        timing.cpu_mean_ns = mean(cpu_ns_);
        timing.update_ns = spread(ns_);
        timing.state_hash = world_.state_hash();
        for (std::size_t i = 0; i < world_.car_count(); ++i) {
            timing.resets += world_.car_resets(i);
            timing.rescues += drivers_.rescues(i);
        }
        return timing;
    }

  private:
    static WorldSettings settings(int threads) {
        WorldSettings settings;
        settings.threads = threads;
        settings.profile = false;
        return settings;
    }

    World world_;
    RaceDrivers drivers_;
    std::vector<double> ns_, cpu_ns_;
};

// The same race on 1 and 2 threads, timed in turns: each world's `warm_up` untimed updates,
// then `updates` timed ones each, in chunks of kChunk updates alternating between the two
// worlds. The host's speed swings by tens of percent over minutes; one race timed after the
// other would see different phases of it, and their ratio would measure the host. Each
// chunk after the first starts with one untimed update: the first update after the other
// world's chunk finds its caches cold and the other pool's worker still spinning, which no
// game's world meets, and as one update in a hundred it would sit exactly on the p99 line.
// Both worlds run as many updates, so their states still agree (docs/benchmarks.md, "A fair
// ratio of threads, and the car ahead in track order").
std::array<RaceTiming, 2> interleaved_races(const cli::DriveScene& scene,
                                            const ColliderPlaneTrees& trees, std::size_t cars,
                                            int warm_up, int updates) {
    constexpr int kChunk = 100;
    TimedRace one(scene, trees, cars, 1, updates);
    TimedRace two(scene, trees, cars, 2, updates);
    one.run(warm_up, false);
    two.run(warm_up, false);
    for (int done = 0; done < updates; done += kChunk) {
        const int chunk = std::min(kChunk, updates - done);
        const int rewarm = done > 0 ? 1 : 0;
        one.run(rewarm, false);
        one.run(chunk, true);
        two.run(rewarm, false);
        two.run(chunk, true);
    }
    return {one.timing(), two.timing()};
}

// A job system for World that runs every island on this thread, timing each, and hands it
// to whichever of `workers` pretend workers has the least CPU time so far: what workers
// claiming islands one by one (largest first, as World orders them) would do on a machine
// with a free core each. Its critical path, the busiest worker's time, is then what the
// update would take on that many threads, whatever else runs on this machine.
struct CriticalPathJobs {
    std::vector<double> worker_ns;

    static void* enqueue(TaskCallback* task, int items, int, void* task_context, void* self) {
        std::vector<double>& busy = static_cast<CriticalPathJobs*>(self)->worker_ns;
        for (int item = 0; item < items; ++item) {
            const auto least = std::min_element(busy.begin(), busy.end());
            const double start = thread_cpu_ns();
            task(item, item + 1, static_cast<int>(least - busy.begin()), task_context);
            *least += thread_cpu_ns() - start;
        }
        return nullptr;  // every item ran
    }
    static void finish(void*, void*) {}
};

// The race of `cars` cars on one thread, as time_race, through CriticalPathJobs: per
// update, the whole update's CPU time over the broad phase plus the busiest of `workers`
// workers' islands, the speed-up the island schedule allows; the mean over the updates.
double island_speed_up(const cli::DriveScene& scene, const ColliderPlaneTrees& trees,
                       std::size_t cars, int workers, int warm_up, int updates) {
    CriticalPathJobs jobs;
    WorldSettings settings;
    settings.profile = false;
    settings.jobs = {&CriticalPathJobs::enqueue, &CriticalPathJobs::finish, &jobs, workers};
    World world(scene.statics, settings, trees);
    RaceDrivers drivers(*scene.track, CarSpec::default_car(), cars);
    drivers.add_cars(world);
    double speed_up = 0.0;
    for (int u = 0; u < warm_up + updates; ++u) {
        drivers.drive(world);
        jobs.worker_ns.assign(static_cast<std::size_t>(workers), 0.0);
        const double start = thread_cpu_ns();
        world.update();
        const double whole = thread_cpu_ns() - start;
        drivers.after_update(world);
        if (u < warm_up) continue;
        double islands = 0.0;
        for (const double ns : jobs.worker_ns) islands += ns;
        const double busiest = *std::max_element(jobs.worker_ns.begin(), jobs.worker_ns.end());
        speed_up += whole / (whole - islands + busiest) / updates;
    }
    return speed_up;
}

// What a pair of cars that do not touch adds to an update, against what one car's static
// contacts cost.
struct PairCost {
    double pair_ns = 0.0;      // median over updates of (both cars) - (each car alone)
    double static_ns = 0.0;    // one car's mid, cull and exact phases per update, mean
    double exact_tests = 0.0;  // ellipsoid pairs per update the culls let through, mean
    // One pair every update, never touching, each car where it is alone.
    bool apart = true;
};

// Two cars side by side on the grid, 3 m apart: their update boxes overlap, so they step
// as an island and test each other every sub-step, and their bounding spheres overlap, so
// the pair test runs its ellipsoid culls too (the worst case of a pair apart). The same
// two cars also run in worlds of their own on the same inputs; alone or together they
// follow the same paths while they do not touch, so update by update the difference is
// the pair's cost. The static contacts: one car's mid, cull and exact phases, their share
// of its update from a profiled run applied to its unprofiled CPU time. Each round starts
// from the grid and lasts 3 s, on the start straight (half throttle, no steering: later
// the cars would leave the road at the first bend).
PairCost time_pair(const cli::DriveScene& scene, const ColliderPlaneTrees& trees, int rounds) {
    constexpr int kWarmUp = 100, kUpdates = 200;
    const CarSpec spec = CarSpec::default_car();
    RaceGridSettings grid;
    grid.column_gap = 3.0;
    grid.row_gap = 0.01;  // side by side: the second car half a row back
    const std::vector<RigidBodyState> starts =
        race_grid(*scene.track, *scene.statics, spec, 2, grid);
    const auto make_world = [&](std::vector<RigidBodyState> cars, bool profile) {
        WorldSettings settings;
        settings.threads = 1;
        settings.profile = profile;
        auto world = std::make_unique<World>(scene.statics, settings, trees);
        for (const RigidBodyState& start : cars) world->add_car(spec, start);
        return world;
    };

    const CarInputs inputs{.throttle = 0.4, .brake = 0.0, .steer = 0.0};
    const double timed = double(rounds) * kUpdates;
    PairCost cost;
    std::vector<double> pair_ns;
    double first_ns = 0.0, static_share = 0.0;
    for (int round = 0; round < rounds; ++round) {
        std::unique_ptr<World> both = make_world(starts, false);
        std::unique_ptr<World> first = make_world({starts[0]}, false);
        std::unique_ptr<World> second = make_world({starts[1]}, false);
        std::unique_ptr<World> profiled = make_world({starts[0]}, true);
        World* worlds[] = {both.get(), first.get(), second.get(), profiled.get()};
        for (int u = 0; u < kWarmUp + kUpdates; ++u) {
            double ns[4];
            for (int w = 0; w < 4; ++w) {
                World& world = *worlds[w];
                for (std::size_t i = 0; i < world.car_count(); ++i) world.car(i).set_inputs(inputs);
                const double start = thread_cpu_ns();
                world.update();
                ns[w] = thread_cpu_ns() - start;
            }
            const UpdateProfile& together = both->last_profile();
            cost.apart = cost.apart && together.car_pairs == 1 && together.car_contacts == 0 &&
                         both->car(0).state().position == first->car(0).state().position &&
                         both->car(1).state().position == second->car(0).state().position;
            if (u < kWarmUp) continue;
            pair_ns.push_back(ns[0] - ns[1] - ns[2]);
            cost.exact_tests += double(together.car_pair_tests) / timed;
            first_ns += ns[1] / timed;
            const UpdateProfile& p = profiled->last_profile();
            static_share +=
                (p[Phase::mid] + p[Phase::cull] + p[Phase::exact]) / p.update_us / timed;
        }
    }
    cost.pair_ns = spread(std::move(pair_ns)).median;
    cost.static_ns = first_ns * static_share;
    return cost;
}

}  // namespace

void bench_race(BenchRun& run) {
    run.progress("race", "default track");
    const cli::DriveScene scene = cli::make_track_scene(kDemoTrackSeed);
    const ColliderPlaneTrees trees = make_collider_plane_trees(*scene.statics);
    const int warm_up = run.quick() ? 100 : 300;
    const int updates = run.quick() ? 200 : 1000;
    double load[1] = {0.0};
    getloadavg(load, 1);  // the threads' ratio needs a free core
    double per_car_worst_us = 0.0;
    std::uint64_t resets_1 = 0, rescues_1 = 0;  // over every field's one-thread race
    double p99_64_on_2_us = 0.0;
    double median_64[3] = {};
    std::uint64_t hash_64[3] = {};
    for (const std::size_t cars : {1, 8, 20, 64, 128}) {
        run.progress("race", std::to_string(cars) + " cars, 1 and 2 threads in turns");
        const std::array<RaceTiming, 2> timings =
            interleaved_races(scene, trees, cars, warm_up, updates);
        for (const int threads : {1, 2}) {
            const RaceTiming& t = timings[threads - 1];
            const std::string name = std::to_string(cars) + " cars, " + std::to_string(threads) +
                                     " thread" + (threads > 1 ? "s" : "");
            const std::string versus =
                threads == 1 ? std::string() : std::to_string(cars) + " cars, 1 thread";
            BenchRow& row = run.add("race", name, t.update_ns.median, versus);
            const double per_car_us = t.mean_ns * 1e-3 / static_cast<double>(cars);
            row.figures = {{"p50_us", t.update_ns.median * 1e-3},
                           {"p99_us", t.update_ns.p99 * 1e-3},
                           {"max_us", t.update_ns.max * 1e-3},
                           {"per_car_us", per_car_us},
                           {"updates", double(updates)}};
            row.note = "wall clock per update, after " + std::to_string(warm_up) +
                       " updates; 1 and 2 threads in turns";
            if (threads == 1) {
                // On one thread its CPU time is the whole update, without others' turns.
                const double cpu_per_car_us = t.cpu_mean_ns * 1e-3 / static_cast<double>(cars);
                row.figures.emplace_back("cpu_per_car_us", cpu_per_car_us);
                per_car_worst_us = std::max(per_car_worst_us, cpu_per_car_us);
                resets_1 += t.resets;
                rescues_1 += t.rescues;
            }
            if (cars == 64) {
                median_64[threads] = t.update_ns.median;
                hash_64[threads] = t.state_hash;
            }
            if (cars == 64 && threads == 2) p99_64_on_2_us = t.update_ns.p99 * 1e-3;
        }
    }
    // Targets as "larger is better" ratios; the threads' lines hold only if both thread
    // counts ended in the same state.
    const bool same_race = hash_64[1] == hash_64[2];
    char evidence[160];
    std::snprintf(evidence, sizeof evidence, "p99 %.0f us", p99_64_on_2_us);
    run.add_target("race: 64 cars on 2 threads, 2 ms / update p99", 2000.0 / p99_64_on_2_us, 1.0,
                   same_race, evidence);
    std::snprintf(evidence, sizeof evidence, "median %.0f us vs %.0f us, load %.1f on %u cores",
                  median_64[1] * 1e-3, median_64[2] * 1e-3, load[0],
                  std::thread::hardware_concurrency());
    run.add_target("race: 64 cars, 2 threads vs 1 (same run)", median_64[1] / median_64[2], 1.8,
                   same_race, evidence);
    // Not a target: what the schedule allows where the load leaves no core free.
    run.progress("race", "64 cars, 2 workers' critical path");
    const double allowed = island_speed_up(scene, trees, 64, 2, warm_up, updates);
    BenchRow& schedule = run.add("race", "64 cars, 2 workers' critical path", 0.0);
    schedule.figures = {{"speed_up", allowed}};
    schedule.note = "thread CPU: 1-thread update over broad phase + busiest worker's islands";
    // A car the reset policy put back skipped the work it would have done.
    std::snprintf(evidence, sizeof evidence,
                  "worst %.1f us CPU per car-update; resets %llu, rescues %llu over the fields",
                  per_car_worst_us, static_cast<unsigned long long>(resets_1),
                  static_cast<unsigned long long>(rescues_1));
    run.add_target("race: 50 us per car-update on 1 thread, any field", 50.0 / per_car_worst_us,
                   1.0, resets_1 == 0, evidence);

    run.progress("race", "a pair of cars apart");
    const PairCost pair = time_pair(scene, trees, run.quick() ? 1 : 5);
    BenchRow& row = run.add("race", "a pair apart, added per update", pair.pair_ns);
    row.figures = {{"pair_us", pair.pair_ns * 1e-3},
                   {"static_contacts_us", pair.static_ns * 1e-3},
                   {"exact_tests_per_update", pair.exact_tests}};
    row.note = "thread CPU: two cars 3 m apart side by side minus each alone";
    std::snprintf(evidence, sizeof evidence, "pair %.1f us vs one car's static contacts %.1f us",
                  pair.pair_ns * 1e-3, pair.static_ns * 1e-3);
    run.add_target("race: a pair apart <= one car's static contacts",
                   pair.static_ns / std::max(pair.pair_ns, 1.0), 1.0, pair.apart, evidence);
}

}  // namespace trackphys::suite
