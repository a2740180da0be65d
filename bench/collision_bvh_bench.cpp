// StaticCollider benchmarks: build time and memory per triangle over 1e3..1e6 triangles
// (1e7 with TRACKPHYS_BENCH_10M=1, run once), query time over the same sizes, and the
// write-up's comparison on a ~300k-triangle banked track: a car's padded swept box with the
// BVH and with brute force, side by side in one run.
//
//   build/release/bench/bench_collision_bvh --benchmark_filter=...
//   TRACKPHYS_BENCH_10M=1 build/release/bench/bench_collision_bvh --benchmark_filter=10M

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <map>
#include <memory>
#include <random>
#include <vector>

#include <benchmark/benchmark.h>

#include "collision/collision_meshes.hpp"
#include "trackphys/collision/brute_force_collider.hpp"
#include "trackphys/collision/static_collider.hpp"
#include "trackphys/collision/static_world.hpp"

namespace trackphys {
namespace {

using test::BankedLoop;

// 1000 km/h for one 10 ms update, and the padding a car box gets for rotation and bounce.
constexpr double kTravel = 2.8;
constexpr double kMargin = 0.25;

std::uint32_t segments_for(std::int64_t triangles) {
    return static_cast<std::uint32_t>(
        std::max<std::int64_t>(3, triangles / (2 * BankedLoop::kAcross)));
}

// The size sweep keeps the triangle density of the 300k-triangle loop at scale 2 (3.6 km,
// ~300 triangles in a padded car box): the loop grows with the triangle count (60 km at
// 1e7), so that the query times show the tree's growth rather than a denser road.
BankedLoop sweep_loop(std::int64_t triangles) {
    return BankedLoop{std::max(0.1, 2.0 * double(triangles) / 300000.0)};
}

const TriangleMesh& loop_mesh(std::int64_t triangles, double scale) {
    static std::map<std::pair<std::int64_t, double>, TriangleMesh> cache;
    auto it = cache.find({triangles, scale});
    if (it == cache.end())
        it = cache
                 .emplace(std::pair{triangles, scale},
                          BankedLoop{scale}.mesh(segments_for(triangles)))
                 .first;
    return it->second;
}

const StaticCollider& loop_collider(std::int64_t triangles, double scale) {
    static std::map<std::pair<std::int64_t, double>, std::unique_ptr<StaticCollider>> cache;
    auto& slot = cache[{triangles, scale}];
    if (!slot) slot = std::make_unique<StaticCollider>(loop_mesh(triangles, scale));
    return *slot;
}

void report_layout(benchmark::State& state, const StaticCollider& collider) {
    const double n = double(collider.triangle_count());
    state.counters["triangles"] = n;
    state.counters["bytes_per_tri"] = double(collider.bytes_used()) / n;
    state.counters["nodes_per_tri"] = double(collider.nodes().size()) / n;
}

void BM_Build(benchmark::State& state) {
    const TriangleMesh& mesh = loop_mesh(state.range(0), sweep_loop(state.range(0)).scale);
    std::unique_ptr<StaticCollider> collider;
    for (auto _ : state) {
        collider.reset();
        collider = std::make_unique<StaticCollider>(mesh);
        benchmark::DoNotOptimize(collider->nodes().data());
    }
    report_layout(state, *collider);
}

// Car boxes at uniform loop parameters in [u_lo, u_hi).
std::vector<Aabb> car_boxes(const BankedLoop& loop, std::size_t count, std::uint64_t seed,
                            double u_lo, double u_hi) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(u_lo, u_hi);
    std::vector<Aabb> boxes;
    for (std::size_t i = 0; i < count; ++i) boxes.push_back(loop.car_box(u(rng), kTravel, kMargin));
    return boxes;
}

// Second argument 0: boxes at random places around the loop (a cold cache at large sizes);
// 1: one car driving at 1000 km/h, a box per 10 ms update (2.8 m apart on average; the
// loop parameter is not arc length), consecutive boxes overlapping, from a fixed start.
void BM_CarBoxQuery(benchmark::State& state) {
    const BankedLoop loop = sweep_loop(state.range(0));
    const StaticCollider& collider = loop_collider(state.range(0), loop.scale);
    std::vector<Aabb> boxes = car_boxes(loop, 10000, 5, 0.0, 1.0);
    if (state.range(1) != 0) {
        const double loop_length = loop.scale * 1820.0;  // m, BankedLoop's perimeter
        boxes.clear();
        for (int k = 0; k < 10000; ++k)
            boxes.push_back(
                loop.car_box(std::fmod(0.37 + k * kTravel / loop_length, 1.0), kTravel, kMargin));
    }
    std::vector<std::uint32_t> out;
    std::size_t i = 0, found = 0;
    for (auto _ : state) {
        out.clear();
        collider.query_aabb(boxes[i], out);
        found += out.size();
        benchmark::DoNotOptimize(out.data());
        i = i + 1 == boxes.size() ? 0 : i + 1;
    }
    state.counters["candidates"] = double(found) / double(state.iterations());
    report_layout(state, collider);
}

// Rays straight down onto the road from 5 m above: one result each, so the time shows the
// tree's depth growth alone.
void BM_Raycast(benchmark::State& state) {
    const BankedLoop loop = sweep_loop(state.range(0));
    const StaticCollider& collider = loop_collider(state.range(0), loop.scale);
    std::mt19937_64 rng(6);
    std::uniform_real_distribution<double> u01(0.0, 1.0), across(-5.5, 5.5);
    std::vector<glm::dvec3> origins;
    for (int k = 0; k < 10000; ++k) {
        const auto f = loop.frame(u01(rng));
        origins.push_back(f.center + f.left * across(rng) + glm::dvec3(0, 5, 0));
    }
    std::size_t i = 0, hits = 0;
    for (auto _ : state) {
        const auto hit = collider.raycast(origins[i], {0, -1, 0}, 50.0);
        hits += hit.has_value();
        benchmark::DoNotOptimize(hit);
        i = i + 1 == origins.size() ? 0 : i + 1;
    }
    state.counters["hit_rate"] = double(hits) / double(state.iterations());
}

// Wheel-sized sphere and swept-sphere (capsule) queries, the mid phase's kinds.
void BM_SphereQuery(benchmark::State& state) {
    const BankedLoop loop = sweep_loop(state.range(0));
    const StaticCollider& collider = loop_collider(state.range(0), loop.scale);
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u01(0.0, 1.0), across(-5.5, 5.5);
    std::vector<glm::dvec3> centers;
    for (int k = 0; k < 10000; ++k) {
        const auto f = loop.frame(u01(rng));
        centers.push_back(f.center + f.left * across(rng) + f.up * 0.3);
    }
    const bool swept = state.range(1) != 0;
    std::vector<std::uint32_t> out;
    std::size_t i = 0, found = 0;
    for (auto _ : state) {
        out.clear();
        if (swept)
            collider.query_capsule(centers[i], centers[i] + glm::dvec3(0.28, 0.0, 0.0), 0.4, out);
        else
            collider.query_sphere(centers[i], 0.4, out);
        found += out.size();
        benchmark::DoNotOptimize(out.data());
        i = i + 1 == centers.size() ? 0 : i + 1;
    }
    state.counters["candidates"] = double(found) / double(state.iterations());
}

// The world broad phase: the 300k loop (scale 2) cut into `chunks` colliders of
// consecutive road pieces (tiles of an open-world map), one car driving: collider boxes
// first, then each hit collider's BVH, into one reused (collider, triangle) buffer.
void BM_WorldCarBox(benchmark::State& state) {
    const BankedLoop loop{2.0};
    const TriangleMesh& mesh = loop_mesh(300000, loop.scale);
    const auto chunks = static_cast<std::size_t>(state.range(0));
    StaticWorld world;
    const std::size_t per_chunk = (mesh.triangles.size() + chunks - 1) / chunks;
    for (std::size_t c = 0; c < chunks; ++c) {
        TriangleMesh chunk{mesh.vertices, {}};
        for (std::size_t t = c * per_chunk;
             t < std::min(mesh.triangles.size(), (c + 1) * per_chunk); ++t)
            chunk.triangles.push_back(mesh.triangles[t]);
        world.add(std::make_shared<const StaticCollider>(chunk));
    }
    const double loop_length = loop.scale * 1820.0;
    std::vector<Aabb> boxes;
    for (int k = 0; k < 10000; ++k)
        boxes.push_back(
            loop.car_box(std::fmod(0.37 + k * kTravel / loop_length, 1.0), kTravel, kMargin));
    std::vector<TriangleRef> out;
    std::size_t i = 0, found = 0;
    for (auto _ : state) {
        out.clear();
        world.query_aabb(boxes[i], out);
        found += out.size();
        benchmark::DoNotOptimize(out.data());
        i = i + 1 == boxes.size() ? 0 : i + 1;
    }
    state.counters["candidates"] = double(found) / double(state.iterations());
}

template <class F>
double median_us(const std::vector<Aabb>& boxes, F&& query) {
    std::vector<double> us;
    us.reserve(boxes.size());
    for (const Aabb& box : boxes) {
        const auto start = std::chrono::steady_clock::now();
        query(box);
        const auto stop = std::chrono::steady_clock::now();
        us.push_back(std::chrono::duration<double, std::micro>(stop - start).count());
    }
    std::nth_element(us.begin(), us.begin() + us.size() / 2, us.end());
    return us[us.size() / 2];
}

// The write-up's comparison: a 300k-triangle banked loop, 10k padded car boxes in the
// tightest banked turn (loop parameter within 0.04 of 0: radius scale * 56 m, banking
// 25 deg); BVH and brute force (1k of the boxes) timed per query in the same run. Loop
// scale (argument / 10): 1 is a dense 1.8 km loop (~540 triangles a box), 2 a 3.6 km loop
// with ~300 a box, the write-up's load (~330).
void BM_Track300k_BvhVsBruteForce(benchmark::State& state) {
    const BankedLoop loop{double(state.range(0)) / 10.0};
    const TriangleMesh& mesh = loop_mesh(300000, loop.scale);
    const StaticCollider& collider = loop_collider(300000, loop.scale);
    const BruteForceCollider brute(mesh);
    std::vector<Aabb> boxes = car_boxes(loop, 10000, 8, -0.04, 0.04);
    std::vector<std::uint32_t> out;
    out.reserve(4096);
    double bvh = 0, brute_force = 0;
    std::size_t candidates = 0;
    for (auto _ : state) {
        bvh = median_us(boxes, [&](const Aabb& box) {
            out.clear();
            collider.query_aabb(box, out);
            benchmark::DoNotOptimize(out.data());
        });
        const std::vector<Aabb> few(boxes.begin(), boxes.begin() + 1000);
        brute_force = median_us(few, [&](const Aabb& box) {
            out.clear();
            brute.query_aabb(box, out);
            benchmark::DoNotOptimize(out.data());
        });
    }
    std::vector<std::size_t> counts;
    for (const Aabb& box : boxes) {
        out.clear();
        collider.query_aabb(box, out);
        counts.push_back(out.size());
        candidates += out.size();
    }
    std::nth_element(counts.begin(), counts.begin() + counts.size() / 2, counts.end());
    state.counters["triangles"] = double(collider.triangle_count());
    state.counters["bvh_median_us"] = bvh;
    state.counters["brute_median_us"] = brute_force;
    state.counters["speedup"] = brute_force / bvh;
    state.counters["candidates_median"] = double(counts[counts.size() / 2]);
    state.counters["candidates_mean"] = double(candidates) / double(boxes.size());
}

BENCHMARK(BM_Build)
    ->RangeMultiplier(10)
    ->Range(1000, 1000000)
    ->Arg(300000)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CarBoxQuery)->ArgsProduct({{1000, 10000, 100000, 300000, 1000000}, {0, 1}});
BENCHMARK(BM_Raycast)->RangeMultiplier(10)->Range(1000, 1000000)->Arg(300000);
BENCHMARK(BM_WorldCarBox)->Arg(1)->Arg(16)->Arg(256);
BENCHMARK(BM_SphereQuery)->Args({300000, 0})->Args({300000, 1});
BENCHMARK(BM_Track300k_BvhVsBruteForce)
    ->Arg(10)
    ->Arg(20)
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond);

// 1e7 triangles: ~1.5 GB and tens of seconds, so only on request, each timed once.
[[maybe_unused]] const bool kHuge = [] {
    const char* flag = std::getenv("TRACKPHYS_BENCH_10M");
    if (flag && flag[0] == '1') {
        benchmark::RegisterBenchmark("BM_Build_10M", BM_Build)
            ->Arg(10000000)
            ->Iterations(1)
            ->Unit(benchmark::kMillisecond);
        benchmark::RegisterBenchmark("BM_CarBoxQuery_10M", BM_CarBoxQuery)
            ->Args({10000000, 0})
            ->Args({10000000, 1});
        benchmark::RegisterBenchmark("BM_Raycast_10M", BM_Raycast)->Arg(10000000);
        return true;
    }
    return false;
}();

}  // namespace
}  // namespace trackphys
