#pragma once

// trackphys-bench: every comparison of the benchmarks in one run. Each group measures its
// cases on the same inputs and adds rows to a BenchRun; main.cpp prints them as one table
// and JSON. The inputs are trackphys_bench_support's (tightest_turn_scene.hpp,
// cull_scene.hpp, midphase_scene.hpp, point_queries.hpp, peers/*.hpp), so this program and
// the Google Benchmark programs measure the same thing.

#include <algorithm>
#include <chrono>
#include <cstddef>
#include <deque>
#include <filesystem>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include <glm/vec3.hpp>

#include "trackphys/dynamics/car.hpp"
#include "trackphys/track/track.hpp"

namespace trackphys::suite {

/// trackphys-bench's options.
struct BenchOptions {
    bool quick = false;
    std::vector<std::string> only;  ///< groups to run; empty: all
    std::filesystem::path json;     ///< where to write the JSON; empty: nowhere
    bool check = false;             ///< fail on a MISS in --quick runs too
};

/// One measured case. median_ns is the median time of one call of the case (ns); ratio is
/// median_ns / the median of the row named `versus` (< 1: faster than it).
struct BenchRow {
    std::string group;
    std::string name;
    double median_ns = 0.0;
    double ratio = 1.0;
    std::string versus;                                   ///< empty: the group's reference row
    std::vector<std::pair<std::string, double>> figures;  ///< extra numbers (units in the key)
    std::string note;                                     ///< what the write-up said, a caveat
};

/// A target of the issue, checked on this run. A speed ratio is met only together with the
/// correctness that goes with it (the same triangle sets, our depth contract held, the
/// drift and the peer's failures reported): `correct` says whether it holds, `evidence` the
/// figures, printed on the target line itself.
struct BenchTarget {
    std::string what;
    double value = 0.0;   ///< measured (a ratio: larger is better)
    double target = 0.0;  ///< at least this
    bool correct = true;
    std::string evidence;
    bool met() const { return correct && value >= target; }
};

/// A peer library and whether this build has it.
struct PeerStatus {
    std::string key;   ///< "bullet" or "fcl" (the JSON key)
    std::string name;  ///< with the version found, e.g. "Bullet 3.24"
    bool built = false;
    std::string detail;  ///< what `built` covers, or how to get it
};

/// The run's settings, its rows and targets, and the progress line on stderr (shown only
/// when stderr is a terminal, as drive's progress bar).
class BenchRun {
  public:
    explicit BenchRun(bool quick);

    bool quick() const { return quick_; }
    /// Repeats of a timed batch: few in --quick, more in the full run.
    int batches(int quick_count, int full_count) const { return quick_ ? quick_count : full_count; }

    /// Shows "[group] what..." on the progress line.
    void progress(const std::string& group, const std::string& what);
    /// Adds a row; its ratio is against the row `versus` of the same group (added before),
    /// or 1 for a reference row (versus empty).
    BenchRow& add(std::string group, std::string name, double median_ns, std::string versus = {});
    void add_target(std::string what, double value, double target, bool correct = true,
                    std::string evidence = {});

    const std::deque<BenchRow>& rows() const { return rows_; }
    const std::vector<BenchTarget>& targets() const { return targets_; }
    /// The row `name` of `group`; throws trackphys::Error if there is none.
    const BenchRow& row(const std::string& group, const std::string& name) const;
    void end_progress();

  private:
    bool quick_;
    bool terminal_;
    std::deque<BenchRow> rows_;  // a deque: add() hands out references that stay valid
    std::vector<BenchTarget> targets_;
};

/// Makes the compiler treat `value` as used and memory as read and written, so a timed call
/// whose result only lands here is neither dropped nor hoisted out of the loop (as Google
/// Benchmark's DoNotOptimize; GCC and Clang).
template <class T>
inline void keep(const T& value) {
    asm volatile("" : : "r,m"(value) : "memory");
}

/// Median over `batches` batches of the time of one call (ns): each batch times `calls`
/// back-to-back calls of f between two steady_clock reads (so clock overhead and jitter
/// stay small against the batch); one untimed batch first warms caches and predictors.
template <class F>
double median_call_ns(F&& f, int calls, int batches) {
    using Clock = std::chrono::steady_clock;
    for (int k = 0; k < calls; ++k) f();
    std::vector<double> ns(static_cast<std::size_t>(batches));
    for (double& t : ns) {
        const auto start = Clock::now();
        for (int k = 0; k < calls; ++k) f();
        t = std::chrono::duration<double, std::nano>(Clock::now() - start).count() / calls;
    }
    std::nth_element(ns.begin(), ns.begin() + batches / 2, ns.end());
    return ns[static_cast<std::size_t>(batches / 2)];
}

/// This thread's CPU time (ns). An update of Bullet's loop takes milliseconds, longer than
/// a time slice on a busy machine: its wall time would count other processes' turns, which
/// a 60 us update mostly escapes, and flatter the ratio.
double thread_cpu_ns();

/// Medians over `batches` batches of the time of one call of each of several functions,
/// taking turns batch by batch, as `now()` (ns) counts it. See median_call_ns_in_turns.
template <class Now>
std::vector<double> median_ns_in_turns(const std::vector<std::function<void()>>& fs, int calls,
                                       int batches, Now&& now) {
    for (const auto& f : fs)
        for (int k = 0; k < calls; ++k) f();
    std::vector<std::vector<double>> ns(fs.size(),
                                        std::vector<double>(static_cast<std::size_t>(batches)));
    for (std::size_t b = 0; b < static_cast<std::size_t>(batches); ++b)
        for (std::size_t i = 0; i < fs.size(); ++i) {
            const double start = now();
            for (int k = 0; k < calls; ++k) fs[i]();
            ns[i][b] = (now() - start) / calls;
        }
    std::vector<double> medians;
    for (std::vector<double>& sample : ns) {
        std::nth_element(sample.begin(), sample.begin() + batches / 2, sample.end());
        medians.push_back(sample[static_cast<std::size_t>(batches / 2)]);
    }
    return medians;
}

/// median_call_ns of several functions whose ratios matter, taking turns batch by batch, so
/// that a busy moment of a shared machine falls on all of them alike. Only for functions
/// that share their data or whose data fits the caches together: turns among many working
/// sets time each one on cold caches.
inline std::vector<double> median_call_ns_in_turns(const std::vector<std::function<void()>>& fs,
                                                   int calls, int batches) {
    using Clock = std::chrono::steady_clock;
    return median_ns_in_turns(fs, calls, batches, [] {
        return std::chrono::duration<double, std::nano>(Clock::now().time_since_epoch()).count();
    });
}

/// median_call_ns_in_turns timed by this thread's CPU time: on a loaded machine a batch
/// that another process interrupts counts its turn in wall time, and the longer of two
/// batches is interrupted more often, which skews their ratio.
inline std::vector<double> median_call_cpu_ns_in_turns(const std::vector<std::function<void()>>& fs,
                                                       int calls, int batches) {
    return median_ns_in_turns(fs, calls, batches, thread_cpu_ns);
}

/// A car driven by autopilot, each update timed.
struct TimedDrive {
    std::vector<double> update_ns;      ///< per update: the thread's CPU time
    std::vector<glm::dvec3> positions;  ///< the car's centre of mass after each update (m)
    double final_speed_kmh = 0.0;
};

/// One car and what advances it by one update (World::update, or the Bullet loop).
struct Driver {
    Car* car;
    std::function<void()> update;
};

/// Drives every driver's car around `track` for `updates` updates, each by its own autopilot
/// (default settings), taking turns by blocks of 10 updates: a busy moment of the shared
/// machine falls on all of them alike, while each block runs with its own data in cache (an
/// update-by-update lockstep would hand ours, ~0.1 ms, the caches Bullet's 6 ms left behind).
std::vector<TimedDrive> drive_timed(const Track& track, const std::vector<Driver>& drivers,
                                    int updates);

/// Median, 99th percentile and maximum of a sample.
struct Spread {
    double median = 0.0, p99 = 0.0, max = 0.0;
};
Spread spread(std::vector<double> sample);

// The groups, in table order. The write-up's improvements (bench_writeup_groups.cpp):
void bench_cull(BenchRun& run);
void bench_roots(BenchRun& run);
void bench_broad_phase(BenchRun& run);
void bench_mid_phase(BenchRun& run);
void bench_update(BenchRun& run);
// A race of many cars (race_group.cpp):
void bench_race(BenchRun& run);
void bench_vehicle(BenchRun& run);
// Baked maps and many colliders (map_groups.cpp):
void bench_maps(BenchRun& run);
void bench_many_colliders(BenchRun& run);
void bench_big_map(BenchRun& run);
// The peers (peer_groups.cpp, pair_group.cpp); each adds a "not built" row when its library
// is absent.
void bench_contact_peers(BenchRun& run);
void bench_pair_peers(BenchRun& run);
void bench_mesh_peers(BenchRun& run);
void bench_update_peers(BenchRun& run);
/// Which peers this build has.
std::vector<PeerStatus> peer_status();
/// The row that says a peer of `group` is not in this build.
void not_built(BenchRun& run, const std::string& group, const std::string& peer);

}  // namespace trackphys::suite
