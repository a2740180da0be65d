// Exact contact kernels: point-ellipsoid root finders and ellipsoid-triangle contact.
//
// Each benchmark runs over a fixed set of 4096 deterministic cases (tests/support), so the
// time per call is the mean over that mix; the counters give root-finder steps per call.
// The */latency benchmarks time every case on its own (32 back-to-back calls, so warm
// caches and predictors) and report the median, 90th percentile and maximum over cases.
//   build/release/bench/bench_contact --benchmark_min_time=0.5

#include <algorithm>
#include <chrono>
#include <vector>

#include <benchmark/benchmark.h>

#include "point_queries.hpp"
#include "support/contact_cases.hpp"
#include "trackphys/geometry/contact.hpp"
#include "trackphys/geometry/point_ellipsoid.hpp"

namespace {

using namespace trackphys;
using bench::point_queries;
using bench::PointQuery;

constexpr int kCases = 4096;

void BM_ClosestPoint(benchmark::State& state, bench::RootFinder finder, test::PointClass kind) {
    const std::vector<PointQuery> queries = point_queries(kind, kCases);
    std::size_t i = 0;
    long iterations = 0, calls = 0;
    int worst = 0;
    for (auto _ : state) {
        const PointQuery& q = queries[i];
        const PointEllipsoid r = bench::closest_point(q, finder);
        benchmark::DoNotOptimize(r);
        iterations += r.iterations;
        worst = std::max(worst, r.iterations);
        ++calls;
        i = i + 1 == queries.size() ? 0 : i + 1;
    }
    state.counters["steps"] = double(iterations) / double(calls);
    state.counters["max_steps"] = worst;
}

/// Median, 90th percentile and maximum over cases of the time of one call (ns), each case
/// timed over 32 consecutive calls.
template <typename Call>
void latency(benchmark::State& state, std::size_t count, Call call) {
    constexpr int kRepeat = 32;
    std::vector<double> ns(count);
    for (auto _ : state) {
        for (std::size_t i = 0; i < count; ++i) {
            const auto start = std::chrono::steady_clock::now();
            for (int k = 0; k < kRepeat; ++k) call(i);
            const auto stop = std::chrono::steady_clock::now();
            ns[i] = std::chrono::duration<double, std::nano>(stop - start).count() / kRepeat;
        }
    }
    std::sort(ns.begin(), ns.end());
    state.counters["median_ns"] = ns[count / 2];
    state.counters["p90_ns"] = ns[count * 9 / 10];
    state.counters["max_ns"] = ns.back();
}

void BM_ClosestPointLatency(benchmark::State& state, bench::RootFinder finder) {
    const std::vector<PointQuery> queries = point_queries(test::PointClass::count, kCases);
    latency(state, queries.size(), [&](std::size_t i) {
        benchmark::DoNotOptimize(bench::closest_point(queries[i], finder));
    });
}

void register_points() {
    const std::pair<const char*, bench::RootFinder> finders[] = {
        {"robust", bench::RootFinder::ours},
        {"writeup_newton5", bench::RootFinder::writeup_newton},
        {"bisection", bench::RootFinder::bisection}};
    for (const auto& [name, finder] : finders) {
        benchmark::RegisterBenchmark((std::string("ClosestPoint/") + name + "/mix").c_str(),
                                     BM_ClosestPoint, finder, test::PointClass::count);
        benchmark::RegisterBenchmark((std::string("ClosestPoint/") + name + "/mix/latency").c_str(),
                                     BM_ClosestPointLatency, finder)
            ->Iterations(1);
        for (int k = 0; k < int(test::PointClass::count); ++k) {
            const auto kind = static_cast<test::PointClass>(k);
            benchmark::RegisterBenchmark(
                (std::string("ClosestPoint/") + name + "/" + test::point_class_name(kind)).c_str(),
                BM_ClosestPoint, finder, kind);
        }
    }
}

enum class ContactSet { road, edge, vertex, deep, miss, hard_mix };

std::vector<test::ContactCase> contact_cases(ContactSet set) {
    test::ContactCaseGenerator generator(777, /*wheel_and_body=*/true);
    std::vector<test::ContactCase> cases;
    while (cases.size() < kCases) {
        switch (set) {
            case ContactSet::road:
                cases.push_back(generator.make(test::ContactKind::road));
                break;
            case ContactSet::edge:
                cases.push_back(generator.make(test::ContactKind::edge));
                break;
            case ContactSet::vertex:
                cases.push_back(generator.make(test::ContactKind::vertex));
                break;
            case ContactSet::deep:
                cases.push_back(generator.make(test::ContactKind::deep));
                break;
            case ContactSet::miss:
                cases.push_back(generator.make(test::ContactKind::miss));
                break;
            case ContactSet::hard_mix:
                cases.push_back(generator.hard_mix());
                break;
        }
    }
    return cases;
}

void BM_Contact(benchmark::State& state, ContactSet set) {
    const std::vector<test::ContactCase> cases = contact_cases(set);
    std::size_t i = 0;
    long overlapping = 0, calls = 0;
    for (auto _ : state) {
        const test::ContactCase& c = cases[i];
        const Contact r = ellipsoid_triangle_contact(c.ellipsoid, c.triangle);
        benchmark::DoNotOptimize(r);
        overlapping += r.depth > 0.0;
        ++calls;
        i = i + 1 == cases.size() ? 0 : i + 1;
    }
    state.counters["overlapping"] = double(overlapping) / double(calls);
}

void BM_ContactLatency(benchmark::State& state, ContactSet set) {
    const std::vector<test::ContactCase> cases = contact_cases(set);
    latency(state, cases.size(), [&](std::size_t i) {
        benchmark::DoNotOptimize(ellipsoid_triangle_contact(cases[i].ellipsoid, cases[i].triangle));
    });
}

void register_contacts() {
    const std::pair<const char*, ContactSet> sets[] = {
        {"road_shallow", ContactSet::road}, {"edge", ContactSet::edge},
        {"vertex", ContactSet::vertex},     {"deep", ContactSet::deep},
        {"miss", ContactSet::miss},         {"hard_mix", ContactSet::hard_mix}};
    for (const auto& [name, set] : sets) {
        benchmark::RegisterBenchmark((std::string("Contact/") + name).c_str(), BM_Contact, set);
        benchmark::RegisterBenchmark((std::string("Contact/") + name + "/latency").c_str(),
                                     BM_ContactLatency, set)
            ->Iterations(1);
    }
}

const int registered = (register_points(), register_contacts(), 0);

}  // namespace
