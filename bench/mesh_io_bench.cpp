// save_mesh, load_mesh and load_mesh's strict check alone on a track-sized mesh (500k
// triangles), per format.
//   build/release/bench/bench_mesh_io
// Writes into the system temporary folder and removes the files afterwards.

#include <filesystem>
#include <string>

#include <benchmark/benchmark.h>

#include "io/file_bytes.hpp"
#include "io/mesh_checks.hpp"
#include "support/grid_mesh.hpp"
#include "trackphys/io/mesh_io.hpp"
#include "trackphys/io/mesh_load_limits.hpp"

namespace {

namespace fs = std::filesystem;

// A 500 x 500 quad height field (250,000 vertices, 500,000 triangles), 0.5 m spacing, with
// gentle waves so that no triangle is degenerate.
const trackphys::TriangleMesh& track_sized_mesh() {
    static const trackphys::TriangleMesh mesh = trackphys::test::grid_mesh(
        500, 500,
        [](int i, int k) { return glm::dvec3(0.5 * i, 0.1 * ((i * 7 + k * 3) % 11), -0.5 * k); });
    return mesh;
}

fs::path bench_file(const std::string& extension) {
    return fs::temp_directory_path() / ("trackphys-bench-mesh-io" + extension);
}

void remove_bench_files(const std::string& extension) {
    fs::remove(bench_file(extension));
    if (extension == ".gltf") fs::remove(bench_file(".bin"));
}

void BM_SaveMesh(benchmark::State& state, const std::string& extension) {
    const trackphys::TriangleMesh& mesh = track_sized_mesh();
    for (auto _ : state) trackphys::save_mesh(mesh, bench_file(extension));
    state.counters["MB"] = static_cast<double>(fs::file_size(bench_file(extension))) / 1e6;
    state.counters["triangles"] = static_cast<double>(mesh.triangles.size());
    remove_bench_files(extension);
}

void BM_LoadMesh(benchmark::State& state, const std::string& extension) {
    trackphys::save_mesh(track_sized_mesh(), bench_file(extension));
    for (auto _ : state) benchmark::DoNotOptimize(trackphys::load_mesh(bench_file(extension)));
    remove_bench_files(extension);
}

// The strict check alone, the file read as load_mesh reads it (src/io/mesh_checks.hpp):
// what bounding the import adds to a load (docs/benchmarks.md).
void BM_CheckMesh(benchmark::State& state, const std::string& extension) {
    const fs::path path = bench_file(extension);
    trackphys::save_mesh(track_sized_mesh(), path);
    const trackphys::detail::MeshFormat format = *trackphys::detail::mesh_format_of(path);
    const trackphys::MeshLoadLimits limits;
    for (auto _ : state) {
        const trackphys::detail::FileBytes file(path);
        benchmark::DoNotOptimize(trackphys::detail::check_mesh(
            file.bytes(), format, path.parent_path(), limits.max_nesting));
    }
    state.counters["MB"] = static_cast<double>(fs::file_size(path)) / 1e6;
    remove_bench_files(extension);
}

}  // namespace

BENCHMARK_CAPTURE(BM_SaveMesh, glb, std::string(".glb"))
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);
BENCHMARK_CAPTURE(BM_SaveMesh, obj, std::string(".obj"))
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);
BENCHMARK_CAPTURE(BM_SaveMesh, ply, std::string(".ply"))
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);
BENCHMARK_CAPTURE(BM_LoadMesh, glb, std::string(".glb"))
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);
BENCHMARK_CAPTURE(BM_LoadMesh, obj, std::string(".obj"))
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);
BENCHMARK_CAPTURE(BM_LoadMesh, ply, std::string(".ply"))
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);
BENCHMARK_CAPTURE(BM_LoadMesh, stl, std::string(".stl"))
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);
BENCHMARK_CAPTURE(BM_CheckMesh, glb, std::string(".glb"))
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);
BENCHMARK_CAPTURE(BM_CheckMesh, obj, std::string(".obj"))
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);
BENCHMARK_CAPTURE(BM_CheckMesh, ply, std::string(".ply"))
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);
BENCHMARK_CAPTURE(BM_CheckMesh, stl, std::string(".stl"))
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);
