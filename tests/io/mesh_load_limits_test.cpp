// MeshLoadLimits (trackphys/io/mesh_load_limits.hpp): each limit refuses a file one beyond
// it, naming the file and the limit, and lets through a file exactly at it.

#include "trackphys/io/mesh_load_limits.hpp"

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>

#include <gtest/gtest.h>
#include <sys/resource.h>

#include "io_test_support.hpp"
#include "trackphys/error.hpp"
#include "trackphys/io/mesh_io.hpp"

namespace trackphys {
namespace {

namespace fs = std::filesystem;

class MeshLoadLimitsTest : public test::ScratchFolderTest {
  protected:
    // The message load_mesh throws for the file under limits; empty when it loads.
    std::string refusal(const std::string& name, const MeshLoadLimits& limits) {
        try {
            load_mesh(file(name), limits);
        } catch (const Error& e) {
            return e.what();
        }
        return {};
    }

    void expect_refused(const std::string& name, const MeshLoadLimits& limits,
                        const std::string& reason) {
        const std::string message = refusal(name, limits);
        EXPECT_NE(message.find("mesh file '" + file(name).string() + "': "), std::string::npos)
            << message;
        EXPECT_NE(message.find(reason), std::string::npos)
            << "expected: " << reason << "\n got: " << message;
    }
};

// Three triangles over five vertices (a fan), 89 bytes.
const std::string kFan =
    "v 0 0 0\nv 1 0 0\nv 1 0 1\nv 0 0 2\nv -1 0 1\nf 1 2 3\nf 1 3 4\nf 1 4 5\n";

// One triangle, placed by a root node and by its two children: three placements.
const std::string kPlacedThrice =
    R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],)"
    R"("nodes":[{"mesh":0,"children":[1,2]},{"mesh":0,"translation":[5,0,0]},)"
    R"({"mesh":0,"translation":[0,0,5]}],)"
    R"("meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],)"
    R"("buffers":[{"byteLength":36,"uri":"data:application/octet-stream;base64,)"
    R"(AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAAAAAAIA/"}],)"
    R"("bufferViews":[{"buffer":0,"byteLength":36}],)"
    R"("accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3",)"
    R"("min":[0,0,0],"max":[1,0,1]}]})";

// Objects nested `depth` deep, the innermost holding one triangle.
std::string nested_ac3d(int depth) {
    std::string text = "AC3Db\n";
    for (int level = 1; level < depth; ++level) text += "OBJECT group\nkids 1\n";
    return text +
           "OBJECT poly\nnumvert 3\n0 0 0\n1 0 0\n0 0 1\nnumsurf 1\nSURF 0x10\nrefs 3\n"
           "0 0 0\n1 0 0\n2 0 0\nkids 0\n";
}

TEST_F(MeshLoadLimitsTest, TrianglesAtTheLimitLoadAndOneMoreIsRefused) {
    test::write_file(file("fan.obj"), kFan);
    MeshLoadLimits limits;
    limits.max_triangles = 3;
    EXPECT_EQ(load_mesh(file("fan.obj"), limits).triangles.size(), 3u);
    limits.max_triangles = 2;
    expect_refused("fan.obj", limits, "more than 2 triangles, the limit max_triangles");
}

// Counted before any is placed: a 1 MB file placing one mesh by 20,000 nodes would otherwise
// take minutes and gigabytes to reach the limit.
TEST_F(MeshLoadLimitsTest, TrianglesCountEveryPlacementOfAnInstancedMesh) {
    test::write_file(file("thrice.gltf"), kPlacedThrice);
    MeshLoadLimits limits;
    limits.max_triangles = 3;
    MeshLoadReport report;
    load_mesh(file("thrice.gltf"), report, limits);
    EXPECT_EQ(report.mesh_instances, 3u);
    EXPECT_EQ(report.triangles, 3u);
    limits.max_triangles = 2;
    report = {};
    expect_refused("thrice.gltf", limits, "more than 2 triangles, the limit max_triangles");
    EXPECT_THROW(load_mesh(file("thrice.gltf"), report, limits), Error);
    EXPECT_EQ(report.mesh_instances, 0u) << "refused before the first was placed";
}

TEST_F(MeshLoadLimitsTest, VerticesAtTheLimitLoadAndOneMoreIsRefused) {
    test::write_file(file("fan.obj"), kFan);
    MeshLoadLimits limits;
    limits.max_vertices = 5;
    EXPECT_EQ(load_mesh(file("fan.obj"), limits).vertices.size(), 5u);
    limits.max_vertices = 4;
    expect_refused("fan.obj", limits, "more than 4 vertices, the limit max_vertices");
}

TEST_F(MeshLoadLimitsTest, BytesAtTheLimitLoadAndOneMoreIsRefused) {
    test::write_file(file("fan.obj"), kFan);
    MeshLoadLimits limits;
    limits.max_bytes = kFan.size();
    EXPECT_EQ(load_mesh(file("fan.obj"), limits).triangles.size(), 3u);
    limits.max_bytes = kFan.size() - 1;
    expect_refused("fan.obj", limits,
                   "the file is " + std::to_string(kFan.size()) + " bytes, more than " +
                       std::to_string(kFan.size() - 1) + ", the limit max_bytes");
}

// A file over the byte limit is refused before it is read: a sparse 4 GiB OBJ (no disk
// used) with a 1000-byte limit leaves the process's peak memory where it was (reading it
// first, as the loader once did, took 4 GiB to refuse it).
TEST_F(MeshLoadLimitsTest, AFileOverTheByteLimitIsRefusedBeforeItIsRead) {
    const fs::path big = file("big.obj");
    test::write_file(big, "v 0 0 0\n");
    fs::resize_file(big, std::uintmax_t{4} << 30);
    rusage before{};
    ::getrusage(RUSAGE_SELF, &before);
    MeshLoadLimits limits;
    limits.max_bytes = 1000;
    expect_refused("big.obj", limits, "the file is 4294967296 bytes, more than 1000");
    rusage after{};
    ::getrusage(RUSAGE_SELF, &after);
    EXPECT_LT(after.ru_maxrss - before.ru_maxrss, 256 * 1024) << "KiB more at the peak";
}

TEST_F(MeshLoadLimitsTest, BytesCountTheBuffersAGltfNames) {
    // The same triangle with its positions in a 36-byte file beside the glTF.
    std::string gltf = kPlacedThrice;
    const std::size_t uri = gltf.find("data:");
    gltf.replace(uri, gltf.find('"', uri) - uri, "tri.bin");
    test::write_file(file("external.gltf"), gltf);
    const float corners[9] = {0, 0, 0, 1, 0, 0, 0, 0, 1};
    test::write_file(file("tri.bin"), std::string(reinterpret_cast<const char*>(corners), 36));
    MeshLoadLimits limits;
    limits.max_bytes = gltf.size() + 36;
    EXPECT_EQ(load_mesh(file("external.gltf"), limits).triangles.size(), 3u);
    limits.max_bytes = gltf.size() + 35;
    expect_refused("external.gltf", limits,
                   "with the buffers it names, it is " + std::to_string(gltf.size() + 36) +
                       " bytes, more than " + std::to_string(gltf.size() + 35) +
                       ", the limit max_bytes");
}

TEST_F(MeshLoadLimitsTest, Ac3dNestingAtTheLimitLoadsAndOneDeeperIsRefused) {
    test::write_file(file("deep.ac"), nested_ac3d(5));
    MeshLoadLimits limits;
    limits.max_nesting = 4;  // kids levels: the innermost object is a kid at depth 4
    EXPECT_EQ(load_mesh(file("deep.ac"), limits).triangles.size(), 1u);
    limits.max_nesting = 3;
    expect_refused("deep.ac", limits, "objects nested deeper than 3, the limit max_nesting");
}

TEST_F(MeshLoadLimitsTest, GltfNodeNestingAtTheLimitLoadsAndOneDeeperIsRefused) {
    test::write_file(file("thrice.gltf"), kPlacedThrice);  // a root and its children: 2 deep
    MeshLoadLimits limits;
    limits.max_nesting = 2;
    EXPECT_EQ(load_mesh(file("thrice.gltf"), limits).triangles.size(), 3u);
    limits.max_nesting = 1;
    expect_refused("thrice.gltf", limits, "nested deeper than 1, the limit max_nesting");
}

// A polygon at the corner limit loads, one corner more is refused before assimp triangulates
// it (its time grows with the square of the corners: 32,000 took 12 s).
TEST_F(MeshLoadLimitsTest, APolygonAtTheCornerLimitLoadsAndOneCornerMoreIsRefused) {
    std::string obj;
    for (int i = 0; i < 8; ++i)
        obj += "v " + std::to_string(std::cos(i * 0.785398)) + " 0 " +
               std::to_string(std::sin(i * 0.785398)) + "\n";
    obj += "f 1 2 3 4 5 6 7 8\n";
    test::write_file(file("octagon.obj"), obj);
    MeshLoadLimits limits;
    limits.max_polygon_corners = 8;
    EXPECT_EQ(load_mesh(file("octagon.obj"), limits).triangles.size(), 6u);
    limits.max_polygon_corners = 7;
    expect_refused("octagon.obj", limits,
                   "face 0 has 8 corners, more than 7, the limit max_polygon_corners");
}

TEST_F(MeshLoadLimitsTest, LimitsThatCannotBeMeantAreRefusedBeforeTheFileIsRead) {
    const fs::path missing = file("missing.obj");
    const auto message = [&missing](const MeshLoadLimits& limits) -> std::string {
        try {
            load_mesh(missing, limits);
        } catch (const Error& e) {
            return e.what();
        }
        return "loaded";
    };
    MeshLoadLimits zero_triangles, zero_vertices, zero_bytes, zero_nesting, too_deep, two_corners;
    zero_triangles.max_triangles = 0;
    zero_vertices.max_vertices = 0;
    zero_bytes.max_bytes = 0;
    zero_nesting.max_nesting = 0;
    too_deep.max_nesting = max_mesh_nesting_allowed + 1;
    two_corners.max_polygon_corners = 2;
    EXPECT_EQ(message(two_corners),
              "MeshLoadLimits::max_polygon_corners is 2: no triangle would load");
    EXPECT_EQ(message(zero_triangles), "MeshLoadLimits::max_triangles is 0: no mesh would load");
    EXPECT_EQ(message(zero_vertices), "MeshLoadLimits::max_vertices is 0: no mesh would load");
    EXPECT_EQ(message(zero_bytes), "MeshLoadLimits::max_bytes is 0: no mesh would load");
    EXPECT_EQ(message(zero_nesting), "MeshLoadLimits::max_nesting is 0: no mesh would load");
    EXPECT_EQ(message(too_deep),
              "MeshLoadLimits::max_nesting is 257, more than the 256 "
              "assimp's recursive readers are safe at");
    too_deep.max_nesting = max_mesh_nesting_allowed;
    EXPECT_NE(message(too_deep).find("no such file"), std::string::npos);
}

// The defaults must let a 50-million-triangle track through in every format: its triangles,
// its vertices even when no two triangles share a corner, and its bytes as ASCII STL, the
// most verbose format (one facet written as a typical exporter does, at 9 significant digits).
TEST(MeshLoadLimitsDefaults, AdmitAFiftyMillionTriangleTrackInEveryFormat) {
    constexpr std::uint64_t kTrackTriangles = 50'000'000;
    const MeshLoadLimits defaults;
    EXPECT_GE(defaults.max_triangles, kTrackTriangles);
    EXPECT_GE(defaults.max_vertices, 3 * kTrackTriangles);
    char vertex[128];
    std::snprintf(vertex, sizeof vertex, "      vertex %.8e %.8e %.8e\n", -1234.56789, -12.3456789,
                  -4321.98765);
    const std::string facet = std::string("  facet normal ") + "-1.00000000e+00 0.00000000e+00 " +
                              "-0.00000000e+00\n    outer loop\n" + vertex + vertex + vertex +
                              "    endloop\n  endfacet\n";
    EXPECT_GE(defaults.max_bytes, kTrackTriangles * facet.size()) << facet.size() << " bytes";
    EXPECT_EQ(defaults.max_nesting, 64u);
}

}  // namespace
}  // namespace trackphys
