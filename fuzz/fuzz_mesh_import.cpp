// libFuzzer target: the mesh importer path we own, bytes -> file -> load_mesh ->
// StaticCollider.
//
// The first byte picks the file extension (so load_mesh picks the reader and its check), the rest
// is the file; TRACKPHYS_FUZZ_MESH_EXTENSION (e.g. ".ply") fixes the extension instead, to search
// one format at a time (docs/testing.md, "Fuzzing"). Every input must end in a mesh that
// StaticCollider accepts, or in trackphys::Error (from load_mesh or from StaticCollider); any other
// exception, crash, sanitizer report, leak or hang is a finding.
//
// assimp itself is Debian's uninstrumented build: libFuzzer sees coverage of trackphys only
// (it learns the formats through our code's reaction to them), and AddressSanitizer checks
// assimp's heap only through its malloc/free/memcpy interceptors. See docs/testing.md, "Fuzzing".

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>
#include <vector>

#include <unistd.h>

#include "trackphys/collision/static_collider.hpp"
#include "trackphys/error.hpp"
#include "trackphys/geometry/aabb.hpp"
#include "trackphys/io/mesh_io.hpp"
#include "trackphys/math/types.hpp"

namespace {

namespace fs = std::filesystem;

// The formats assimp reads that a track could plausibly come in, text and binary.
constexpr std::array<const char*, 7> kExtensions = {".obj", ".ply", ".stl", ".gltf",
                                                    ".glb", ".ac",  ".off"};

// Larger inputs only slow the search down: every reader's structure shows in a few KB.
constexpr std::size_t kMaxInput = 64 * 1024;

[[noreturn]] void finding(const std::string& what) {
    std::fprintf(stderr, "fuzz_mesh_import: %s\n", what.c_str());
    std::abort();
}

// One folder per process (libFuzzer's -jobs/-fork run several): the input file and any
// file a .gltf names beside it land there. Removed at exit (libFuzzer exits normally at the
// end of a run; after a crash it stays, with the input that caused it).
struct WorkFolder {
    fs::path path;
    WorkFolder()
        : path(fs::temp_directory_path() / ("trackphys_fuzz_mesh_" + std::to_string(getpid()))) {
        fs::create_directories(path);
    }
    ~WorkFolder() {
        std::error_code ignored;
        fs::remove_all(path, ignored);
    }
};

const fs::path& work_folder() {
    static const WorkFolder folder;
    return folder.path;
}

void check_mesh(const trackphys::TriangleMesh& mesh, const trackphys::MeshLoadReport& report) {
    if (mesh.triangles.empty()) finding("load_mesh returned a mesh without triangles");
    if (report.triangles != mesh.triangles.size() || report.vertices != mesh.vertices.size())
        finding("load_mesh's report disagrees with its mesh");
    for (const glm::dvec3& v : mesh.vertices)
        if (!trackphys::is_finite(v)) finding("load_mesh returned a non-finite vertex");
    for (const auto& t : mesh.triangles)
        for (const std::uint32_t i : t)
            if (i >= mesh.vertices.size()) finding("load_mesh returned an index out of range");
}

void exercise_collider(const trackphys::TriangleMesh& mesh, const trackphys::Aabb& bounds) {
    const trackphys::StaticCollider collider(mesh);
    // A query over the whole mesh must find every kept triangle exactly once.
    std::vector<std::uint32_t> hits;
    collider.query_aabb(bounds, hits);
    std::sort(hits.begin(), hits.end());
    if (std::adjacent_find(hits.begin(), hits.end()) != hits.end())
        finding("query_aabb returned a triangle twice");
    if (hits.size() != collider.triangle_count())
        finding("query_aabb over the mesh bounds missed kept triangles");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size < 1 || size > kMaxInput) return -1;  // -1: not added to the corpus
    static const char* const fixed_extension = std::getenv("TRACKPHYS_FUZZ_MESH_EXTENSION");
    const char* extension =
        fixed_extension != nullptr ? fixed_extension : kExtensions[data[0] % kExtensions.size()];
    const fs::path path = work_folder() / (std::string("input") + extension);
    {
        std::ofstream out(path, std::ios::binary | std::ios::trunc);
        out.write(reinterpret_cast<const char*>(data + 1), static_cast<std::streamsize>(size - 1));
        if (!out) finding("cannot write " + path.string());
    }
    try {
        trackphys::MeshLoadReport report;
        const trackphys::TriangleMesh mesh = trackphys::load_mesh(path, report);
        check_mesh(mesh, report);
        exercise_collider(mesh, report.bounds);
    } catch (const trackphys::Error&) {
        // A defined rejection: what bad input must get.
    } catch (const std::exception& e) {
        finding(std::string("escaped exception other than trackphys::Error: ") + e.what());
    }
    return 0;
}
