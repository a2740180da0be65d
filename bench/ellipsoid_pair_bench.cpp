// The exact ellipsoid-ellipsoid contact, by family of pairs (tests/support).
//
// Each benchmark runs over 4096 deterministic pairs of one family, so the time per call is
// the mean over that family; the counters give the share of each certificate path and the
// evaluations of the support function per call. The */latency benchmarks time every pair
// on its own (32 back-to-back calls) and report the median, 90th percentile and maximum.
//   build/release/bench/bench_ellipsoid_pair --benchmark_min_time=0.5

#include <algorithm>
#include <chrono>
#include <vector>

#include <benchmark/benchmark.h>

#include "geometry/ellipsoid_pair_kernel.hpp"
#include "support/ellipsoid_pair_cases.hpp"
#include "trackphys/geometry/ellipsoid_pair.hpp"

namespace {

using namespace trackphys;
using test::PairCase;
using test::PairKind;

constexpr int kCases = 4096;

std::vector<PairCase> pairs(PairKind kind) {
    test::PairCaseGenerator generator(4242 + static_cast<int>(kind));
    std::vector<PairCase> out;
    out.reserve(kCases);
    for (int i = 0; i < kCases; ++i) out.push_back(generator.make(kind));
    return out;
}

void BM_Pair(benchmark::State& state, PairKind kind) {
    const std::vector<PairCase> cases = pairs(kind);
    std::size_t i = 0;
    for (auto _ : state) {
        const Contact c = ellipsoid_ellipsoid_contact(cases[i].a, cases[i].b);
        benchmark::DoNotOptimize(c);
        i = i + 1 == cases.size() ? 0 : i + 1;
    }
    long paths[5] = {0, 0, 0, 0, 0}, evaluations = 0;
    for (const PairCase& c : cases) {
        const detail::PairSolution s = detail::pair_solution(c.a, c.b);
        ++paths[static_cast<int>(s.path)];
        evaluations += s.evaluations;
    }
    state.counters["separated"] = double(paths[0]) / kCases;
    state.counters["inscribed"] = double(paths[1]) / kCases;
    state.counters["searched"] = double(paths[2]) / kCases;
    state.counters["unproven"] = double(paths[3]) / kCases;
    state.counters["evals"] = double(evaluations) / kCases;
}

/// ellipsoids_may_touch with a 0.5 m reach: far pairs are rejected by a certificate.
void BM_MayTouch(benchmark::State& state, PairKind kind) {
    const std::vector<PairCase> cases = pairs(kind);
    std::size_t i = 0;
    long rejected = 0, calls = 0;
    for (auto _ : state) {
        const bool may = ellipsoids_may_touch(cases[i].a, cases[i].b, 0.5);
        benchmark::DoNotOptimize(may);
        rejected += !may;
        ++calls;
        i = i + 1 == cases.size() ? 0 : i + 1;
    }
    state.counters["rejected"] = double(rejected) / double(calls);
}

void BM_PairLatency(benchmark::State& state, PairKind kind) {
    const std::vector<PairCase> cases = pairs(kind);
    constexpr int kRepeat = 32;
    std::vector<double> ns(cases.size());
    for (auto _ : state) {
        for (std::size_t i = 0; i < cases.size(); ++i) {
            const auto start = std::chrono::steady_clock::now();
            for (int k = 0; k < kRepeat; ++k)
                benchmark::DoNotOptimize(ellipsoid_ellipsoid_contact(cases[i].a, cases[i].b));
            const auto stop = std::chrono::steady_clock::now();
            ns[i] = std::chrono::duration<double, std::nano>(stop - start).count() / kRepeat;
        }
    }
    std::sort(ns.begin(), ns.end());
    state.counters["median_ns"] = ns[ns.size() / 2];
    state.counters["p90_ns"] = ns[ns.size() * 9 / 10];
    state.counters["max_ns"] = ns.back();
}

void register_all() {
    benchmark::RegisterBenchmark("BM_MayTouch/far", BM_MayTouch, PairKind::far);
    benchmark::RegisterBenchmark("BM_MayTouch/car_like", BM_MayTouch, PairKind::car_like);
    for (const PairKind kind :
         {PairKind::car_like, PairKind::grazing, PairKind::far, PairKind::sphere_ellipsoid,
          PairKind::deep, PairKind::elongated, PairKind::crossing, PairKind::coincident}) {
        const std::string name = test::pair_kind_name(kind);
        benchmark::RegisterBenchmark(("BM_Pair/" + name).c_str(), BM_Pair, kind);
        benchmark::RegisterBenchmark(("BM_PairLatency/" + name).c_str(), BM_PairLatency, kind)
            ->Iterations(1)
            ->Unit(benchmark::kMillisecond);
    }
}

const int registered = (register_all(), 0);

}  // namespace
