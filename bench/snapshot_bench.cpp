// Snapshots of one car on the default track (seed 7, ~60 colliders, 300k triangles), after
// 200 updates by autopilot: World::save_state / restore_state, and the file format's
// encode / decode and atomic write. The counter `bytes` is the snapshot file's size.
#include <filesystem>
#include <memory>

#include <benchmark/benchmark.h>

#include "trackphys/collision/static_collider.hpp"
#include "trackphys/io/snapshot_file.hpp"
#include "trackphys/track/track.hpp"
#include "trackphys/world/autopilot.hpp"
#include "trackphys/world/world.hpp"

namespace {

using namespace trackphys;

struct Scene {
    std::unique_ptr<World> world;
    WorldSnapshot snapshot;
    std::string bytes;
};

const Scene& scene() {
    static const Scene built = [] {
        TrackParams params;
        params.seed = kDemoTrackSeed;
        const Track track = generate_track(params);
        auto statics = std::make_shared<StaticWorld>();
        for (const TrackChunk& chunk : track.chunks)
            statics->add(std::make_shared<StaticCollider>(chunk.mesh));
        Scene s;
        s.world = std::make_unique<World>(statics);
        const CarSpec spec = CarSpec::default_car();
        const CenterlineSample& start = track.centerline.front();
        RigidBodyState state;
        state.position = start.position + start.up * (spec.lowest_point_depth() + 0.001);
        state.orientation =
            glm::normalize(glm::quat_cast(glm::dmat3(start.left, start.up, start.tangent)));
        s.world->add_car(spec, state);
        Autopilot pilot(track, spec);
        for (int i = 0; i < 200; ++i) {
            s.world->car(0).set_inputs(pilot.drive(s.world->car(0)));
            s.world->update();
        }
        s.snapshot = s.world->save_state();
        s.bytes = encode_snapshot(s.snapshot);
        return s;
    }();
    return built;
}

void BM_SaveState(benchmark::State& state) {
    const Scene& s = scene();
    for (auto _ : state) benchmark::DoNotOptimize(s.world->save_state());
    state.counters["bytes"] = static_cast<double>(s.bytes.size());
}
BENCHMARK(BM_SaveState)->Unit(benchmark::kMicrosecond);

// Into a kept snapshot, as rollback netcode saves every frame: no allocation.
void BM_SaveStateInto(benchmark::State& state) {
    const Scene& s = scene();
    WorldSnapshot into;
    for (auto _ : state) {
        s.world->save_state(into);
        benchmark::DoNotOptimize(into);
    }
}
BENCHMARK(BM_SaveStateInto)->Unit(benchmark::kMicrosecond);

void BM_RestoreState(benchmark::State& state) {
    const Scene& s = scene();
    for (auto _ : state) s.world->restore_state(s.snapshot);
}
BENCHMARK(BM_RestoreState)->Unit(benchmark::kMicrosecond);

void BM_EncodeSnapshot(benchmark::State& state) {
    const Scene& s = scene();
    for (auto _ : state) benchmark::DoNotOptimize(encode_snapshot(s.snapshot));
    state.counters["bytes"] = static_cast<double>(s.bytes.size());
}
BENCHMARK(BM_EncodeSnapshot)->Unit(benchmark::kMicrosecond);

void BM_DecodeSnapshot(benchmark::State& state) {
    const Scene& s = scene();
    for (auto _ : state) benchmark::DoNotOptimize(decode_snapshot(s.bytes));
}
BENCHMARK(BM_DecodeSnapshot)->Unit(benchmark::kMicrosecond);

void BM_SaveSnapshotFile(benchmark::State& state) {
    const Scene& s = scene();
    const std::filesystem::path path =
        std::filesystem::temp_directory_path() / "trackphys_bench.snap";
    for (auto _ : state) save_snapshot(path, s.snapshot);
    std::filesystem::remove(path);
}
BENCHMARK(BM_SaveSnapshotFile)->Unit(benchmark::kMicrosecond);

}  // namespace
