// load_mesh on hand-written files: what it keeps, drops, counts and where it puts things.

#include <array>
#include <cmath>
#include <new>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "io_test_support.hpp"
#include "trackphys/collision/static_collider.hpp"
#include "trackphys/geometry/triangle.hpp"
#include "trackphys/io/mesh_io.hpp"

namespace trackphys {
namespace {

namespace fs = std::filesystem;

Triangle triangle(const TriangleMesh& mesh, std::size_t t) {
    const auto& i = mesh.triangles[t];
    return Triangle(mesh.vertices[i[0]], mesh.vertices[i[1]], mesh.vertices[i[2]]);
}

class MeshImport : public test::ScratchFolderTest {};

TEST_F(MeshImport, ObjKeepsCoordinatesAndWindingAsWritten) {
    // No axis conversion: a triangle in the XZ plane, counter-clockwise seen from +Y.
    test::write_file(file("t.obj"), "v 1.5 2.25 -3\nv 2.5 2.25 -3\nv 1.5 2.25 -4\nf 1 2 3\n");
    MeshLoadReport report;
    const TriangleMesh mesh = load_mesh(file("t.obj"), report);
    ASSERT_EQ(mesh.triangles.size(), 1u);
    EXPECT_EQ(triangle(mesh, 0).vertices,
              (std::array<glm::dvec3, 3>{glm::dvec3(1.5, 2.25, -3), glm::dvec3(2.5, 2.25, -3),
                                         glm::dvec3(1.5, 2.25, -4)}));
    EXPECT_EQ(triangle(mesh, 0).normal(), glm::dvec3(0, 1, 0));
    EXPECT_EQ(report.mesh_instances, 1u);
    EXPECT_EQ(report.area, 0.5);
    EXPECT_EQ(report.bounds.min, glm::dvec3(1.5, 2.25, -4));
    EXPECT_EQ(report.bounds.max, glm::dvec3(2.5, 2.25, -3));
}

// Some editors begin a text file with a UTF-8 byte order mark. The check refused the first
// statement ('\xEF\xBB\xBFv' is not read), and assimp's reader lost it (the face's vertex 1).
TEST_F(MeshImport, ObjAfterAByteOrderMarkLoads) {
    test::write_file(file("bom.obj"), "\xEF\xBB\xBFv 0 0 0\nv 1 0 0\nv 0 0 -1\nf 1 2 3\n");
    const TriangleMesh mesh = load_mesh(file("bom.obj"));
    ASSERT_EQ(mesh.triangles.size(), 1u);
    EXPECT_EQ(triangle(mesh, 0).vertices[0], glm::dvec3(0.0));
}

TEST_F(MeshImport, PolygonsAreTriangulated) {
    // A unit quad and a convex pentagon: 2 + 3 triangles covering their whole area.
    test::write_file(file("p.obj"),
                     "v 0 0 0\nv 1 0 0\nv 1 0 -1\nv 0 0 -1\n"
                     "v 3 0 0\nv 5 0 0\nv 5 0 -2\nv 4 0 -3\nv 3 0 -2\n"
                     "f 1 2 3 4\nf 5 6 7 8 9\n");
    MeshLoadReport report;
    const TriangleMesh mesh = load_mesh(file("p.obj"), report);
    EXPECT_EQ(report.triangles, 5u);
    EXPECT_EQ(report.triangulation_lost, 0u);
    EXPECT_DOUBLE_EQ(report.area, 1.0 + 4.0 + 1.0);
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
        EXPECT_EQ(triangle(mesh, t).normal(), glm::dvec3(0, 1, 0)) << "triangle " << t;
}

TEST_F(MeshImport, TrianglesAssimpFailsToTriangulateAreCounted) {
    // A self-intersecting 7-gon (found by a seeded search): assimp's ear clipping finds no
    // ear after two triangles and silently drops the other three of its n - 2 = 5.
    test::write_file(file("knot.obj"),
                     "v 2 0 -3\nv 1 0 -4\nv 2 0 -1\nv 1 0 -1\nv 4 0 -2\nv 3 0 -4\nv 1 0 0\n"
                     "f 1 2 3 4 5 6 7\n");
    MeshLoadReport report;
    load_mesh(file("knot.obj"), report);
    EXPECT_EQ(report.triangles, 2u);
    EXPECT_EQ(report.degenerate_dropped, 0u);
    EXPECT_EQ(report.triangulation_lost, 3u);
}

TEST_F(MeshImport, DegenerateTrianglesAreDroppedAndCounted) {
    test::write_file(file("d.obj"),
                     "v 0 0 0\nv 1 0 0\nv 0 0 -1\nv 1 0 -1\n"  // 1-4: two good triangles
                     "v 2 0 0\nv 3 0 0\nv 4 0 0\n"             // 5-7: collinear
                     "v 0.5 1e-14 0\n"                         // 8: 1e-14 off the edge 1-2
                     "v 7 7 7\n"                               // 9: only in dropped triangles
                     "f 1 2 3\nf 2 4 3\n"
                     "f 5 6 7\n"    // collinear
                     "f 1 1 3\n"    // repeated corner
                     "f 9 9 9\n"    // a point as a triangle
                     "f 1 8 2\n");  // sliver: height 1e-14 over a 1 m edge
    MeshLoadReport report;
    const TriangleMesh mesh = load_mesh(file("d.obj"), report);
    EXPECT_EQ(report.triangles, 2u);
    EXPECT_EQ(report.degenerate_dropped, 4u);
    // Vertices only dropped triangles use are left out.
    EXPECT_EQ(mesh.vertices.size(), 4u);
    EXPECT_EQ(report.vertices, 4u);
    EXPECT_EQ(report.bounds.max, glm::dvec3(1, 0, 0));
    EXPECT_DOUBLE_EQ(report.area, 1.0);
}

TEST_F(MeshImport, PointsAndLinesAreSkippedAndCounted) {
    test::write_file(file("pl.obj"),
                     "v 0 0 0\nv 1 0 0\nv 0 0 -1\nv 2 2 2\n"
                     "p 1 2\n"    // two points
                     "l 1 2 4\n"  // a polyline: two segments
                     "f 1 2 3\n");
    MeshLoadReport report;
    const TriangleMesh mesh = load_mesh(file("pl.obj"), report);
    EXPECT_EQ(report.triangles, 1u);
    EXPECT_EQ(report.points_skipped, 2u);
    EXPECT_EQ(report.lines_skipped, 2u);
    EXPECT_EQ(report.degenerate_dropped, 0u);
    EXPECT_EQ(mesh.vertices.size(), 3u);  // (2, 2, 2) belongs to a line only
}

TEST_F(MeshImport, IdenticalPositionsAreWelded) {
    // Two triangles sharing an edge, the shared corners written twice (as STL would), one
    // first as -0: the welder keys a position by its bits, which tell -0 from +0, so it
    // stores +0 for both.
    test::write_file(file("w.obj"),
                     "v 0 0 0\nv 1 0 0\nv 0 -0 -1\n"
                     "v 1 0 0\nv 1 0 -1\nv 0 0 -1\n"
                     "f 1 2 3\nf 4 5 6\n");
    const TriangleMesh mesh = load_mesh(file("w.obj"));
    ASSERT_EQ(mesh.triangles.size(), 2u);
    EXPECT_EQ(mesh.vertices.size(), 4u);
    EXPECT_EQ(mesh.triangles[0][1], mesh.triangles[1][0]);  // (1, 0, 0)
    EXPECT_EQ(mesh.triangles[0][2], mesh.triangles[1][2]);  // (0, 0, -1), once (0, -0, -1)
    EXPECT_FALSE(std::signbit(mesh.vertices[mesh.triangles[0][2]].y));
}

TEST_F(MeshImport, DuplicateTrianglesAreDroppedAndCounted) {
    test::write_file(file("dup.obj"),
                     "v 0 0 0\nv 1 0 0\nv 0 0 -1\nv 1 0 -1\n"
                     "v 1 0 0\n"  // 5: vertex 2 written again (welded)
                     "usemtl road\nf 1 2 3\nf 2 4 3\n"
                     "usemtl grass\n"
                     "f 3 2 1\n"    // the first, wound the other way
                     "f 3 1 5\n"    // the first again, through the welded copy of vertex 2
                     "f 2 4 1\n");  // two corners of the first: another triangle
    MeshLoadReport report;
    const TriangleMesh mesh = load_mesh(file("dup.obj"), report);
    ASSERT_EQ(mesh.triangles.size(), 3u);
    EXPECT_EQ(report.triangles, 3u);
    EXPECT_EQ(report.duplicates_dropped, 2u);
    EXPECT_EQ(report.degenerate_dropped, 0u);
    EXPECT_DOUBLE_EQ(report.area, 1.5);
    // The first of each is kept, with its winding and its surface.
    EXPECT_EQ(triangle(mesh, 0).normal(), glm::dvec3(0, 1, 0));
    ASSERT_EQ(mesh.surfaces.size(), 3u);
    const std::vector<std::string> materials{report.materials[mesh.surfaces[0]],
                                             report.materials[mesh.surfaces[1]],
                                             report.materials[mesh.surfaces[2]]};
    EXPECT_EQ(materials, (std::vector<std::string>{"road", "road", "grass"}));
}

// A double-sided export lists every face twice, the second wound the other way: it loads as
// its one side, bit for bit, so it drives as that side does.
TEST_F(MeshImport, ADoubleSidedExportLoadsAsItsOneSide) {
    std::string vertices, one_side, both_sides;
    constexpr int n = 20;
    for (int i = 0; i <= n; ++i)
        for (int k = 0; k <= n; ++k)
            vertices += "v " + std::to_string(i) + " " + std::to_string((i * k) % 7 * 0.1) + " " +
                        std::to_string(-k) + "\n";
    for (int i = 0; i < n; ++i)
        for (int k = 0; k < n; ++k) {
            const int a = i * (n + 1) + k + 1, b = a + n + 1;  // OBJ counts from 1
            for (const auto& [p, q, r] : {std::array{a, b, a + 1}, std::array{b, b + 1, a + 1}}) {
                const std::string face =
                    std::to_string(p) + " " + std::to_string(q) + " " + std::to_string(r) + "\n";
                one_side += "f " + face;
                both_sides += "f " + face + "f " + std::to_string(r) + " " + std::to_string(q) +
                              " " + std::to_string(p) + "\n";
            }
        }
    test::write_file(file("one.obj"), vertices + one_side);
    test::write_file(file("both.obj"), vertices + both_sides);
    MeshLoadReport one_report, both_report;
    const TriangleMesh one = load_mesh(file("one.obj"), one_report);
    const TriangleMesh both = load_mesh(file("both.obj"), both_report);
    ASSERT_EQ(one.triangles.size(), 2u * n * n);
    EXPECT_EQ(one_report.duplicates_dropped, 0u);
    EXPECT_EQ(both_report.duplicates_dropped, 2u * n * n);
    EXPECT_EQ(both.vertices, one.vertices);
    EXPECT_EQ(both.triangles, one.triangles);
    EXPECT_EQ(both.surfaces, one.surfaces);
    EXPECT_EQ(both_report.area, one_report.area);
}

// A strip of 2n triangles over 2n + 2 vertices as OBJ text.
std::string strip_obj(int n) {
    std::string text;
    for (int i = 0; i <= n; ++i)
        text += "v " + std::to_string(i) + " 0 0\nv " + std::to_string(i) + " 0 -1\n";
    for (int i = 0; i < n; ++i) {
        const int a = 2 * i + 1;  // OBJ counts from 1
        text += "f " + std::to_string(a) + " " + std::to_string(a + 2) + " " +
                std::to_string(a + 1) + "\nf " + std::to_string(a + 1) + " " +
                std::to_string(a + 2) + " " + std::to_string(a + 3) + "\n";
    }
    return text;
}

TEST_F(MeshImport, ProgressHearsOfTheTrianglesPlaced) {
    test::write_file(file("strip.obj"), strip_obj(70000));
    std::vector<std::pair<std::size_t, std::size_t>> heard;
    MeshLoadReport report;
    const TriangleMesh mesh =
        load_mesh(file("strip.obj"), report, MeshLoadLimits{},
                  [&](std::size_t done, std::size_t total) { heard.emplace_back(done, total); });
    ASSERT_EQ(mesh.triangles.size(), 140000u);
    const std::vector<std::pair<std::size_t, std::size_t>> expected{
        {0, 140000}, {65536, 140000}, {131072, 140000}, {140000, 140000}};
    EXPECT_EQ(heard, expected);
}

TEST_F(MeshImport, ProgressThatThrowsCancelsTheLoadWithItsOwnException) {
    test::write_file(file("strip.obj"), strip_obj(70000));
    struct Stop {};
    MeshLoadReport report;
    std::size_t calls = 0;
    EXPECT_THROW(load_mesh(file("strip.obj"), report, MeshLoadLimits{},
                           [&](std::size_t done, std::size_t) {
                               ++calls;
                               if (done > 0) throw Stop{};
                           }),
                 Stop);
    EXPECT_EQ(calls, 2u);  // the start, and the first report after it
    // A standard exception is not worded as the reader's ("import failed: ...").
    try {
        load_mesh(file("strip.obj"), report, MeshLoadLimits{},
                  [](std::size_t, std::size_t) { throw std::runtime_error("cancelled"); });
        ADD_FAILURE() << "no exception";
    } catch (const Error& e) {
        ADD_FAILURE() << "worded as the reader's: " << e.what();
    } catch (const std::runtime_error& e) {
        EXPECT_STREQ(e.what(), "cancelled");
    }
    // Nor is an allocation failure worded as the file's ("out of memory while reading it").
    EXPECT_THROW(load_mesh(file("strip.obj"), report, MeshLoadLimits{},
                           [](std::size_t, std::size_t) { throw std::bad_alloc(); }),
                 std::bad_alloc);
}

TEST_F(MeshImport, AllObjectsOfAFileAreMerged) {
    test::write_file(file("two.obj"),
                     "o first\nv 0 0 0\nv 1 0 0\nv 0 0 -1\nf 1 2 3\n"
                     "o second\nv 10 0 0\nv 11 0 0\nv 10 0 -1\nf 4 5 6\n");
    MeshLoadReport report;
    const TriangleMesh mesh = load_mesh(file("two.obj"), report);
    EXPECT_EQ(report.mesh_instances, 2u);
    EXPECT_EQ(mesh.triangles.size(), 2u);
    EXPECT_EQ(report.bounds.min, glm::dvec3(0, 0, -1));
    EXPECT_EQ(report.bounds.max, glm::dvec3(11, 0, 0));
}

// One triangle in the XZ plane facing +Y, placed by a three-level hierarchy:
//   parent: translation (10, 0, 0)
//     child: rotation 90 degrees about +Y, uniform scale 2  -> places the mesh
//     mirror: scale (-1, 1, 1)                              -> places the mesh again
//   other root: the identity, with the mesh
// A 90 degree turn about +Y maps (x, y, z) to (z, y, -x).
TEST_F(MeshImport, GltfNodeTransformsAreComposedAndApplied) {
    const std::vector<float> positions{0, 0, 0, 1, 0, 0, 0, 0, -1};
    const std::vector<std::uint32_t> indices{0, 1, 2};
    const std::string nodes =
        R"({"name":"parent","translation":[10,0,0],"children":[1,2]},)"
        R"({"name":"child","rotation":[0,0.70710678118654752,0,0.70710678118654752],)"
        R"("scale":[2,2,2],"mesh":0},)"
        R"({"name":"mirror","scale":[-1,1,1],"mesh":0},)"
        R"({"name":"plain","mesh":0})";
    test::write_gltf(file("h.gltf"), positions, indices, nodes, "0,3");

    MeshLoadReport report;
    const TriangleMesh mesh = load_mesh(file("h.gltf"), report);
    EXPECT_EQ(report.mesh_instances, 3u);
    EXPECT_EQ(report.mirrored_instances, 1u);
    ASSERT_EQ(mesh.triangles.size(), 3u);

    // Triangles come out in node order: child, mirror, plain.
    const std::array<std::array<glm::dvec3, 3>, 3> expected{{
        {glm::dvec3(10, 0, 0), glm::dvec3(10, 0, -2), glm::dvec3(8, 0, 0)},
        // mirrored: corners 1 and 2 swapped so the triangle keeps facing +Y
        {glm::dvec3(10, 0, 0), glm::dvec3(10, 0, -1), glm::dvec3(9, 0, 0)},
        {glm::dvec3(0, 0, 0), glm::dvec3(1, 0, 0), glm::dvec3(0, 0, -1)},
    }};
    for (std::size_t t = 0; t < 3; ++t) {
        const Triangle got = triangle(mesh, t);
        for (std::size_t k = 0; k < 3; ++k)
            EXPECT_LT(glm::distance(got.vertices[k], expected[t][k]), 1e-6)
                << "triangle " << t << " corner " << k;
        // glTF is +Y up like trackphys: no axis conversion, and mirroring keeps the facing.
        EXPECT_NEAR(got.normal().y, 1.0, 1e-12) << "triangle " << t;
    }
    EXPECT_NEAR(report.area, 0.5 * (4.0 + 1.0 + 1.0), 1e-6);
}

// Each triangle's surface id is its mesh's material index; the report names the materials.
TEST_F(MeshImport, GltfMaterialsBecomeSurfaceIds) {
    const std::vector<float> positions{0, 0, 0, 0, 0, -1, 1, 0, 0, 1, 0, -1};
    const std::vector<std::uint32_t> indices{0, 1, 2, 2, 1, 3};
    test::write_gltf(
        file("m.gltf"), positions, indices,
        R"({"mesh":0},{"mesh":1,"translation":[10,0,0]},{"mesh":0,"translation":[20,0,0]})",
        "0,1,2");
    std::string json = test::read_file(file("m.gltf"));
    const std::string one_mesh =
        R"("meshes":[{"name":"road","primitives":[{"attributes":{"POSITION":0},"indices":1,"mode":4}]}])";
    const std::size_t at = json.find(one_mesh);
    ASSERT_NE(at, std::string::npos) << json;
    json.replace(
        at, one_mesh.size(),
        R"("materials":[{"name":"asphalt"},{"name":"grass"}],"meshes":[)"
        R"({"name":"road","primitives":[{"attributes":{"POSITION":0},"indices":1,"material":0}]},)"
        R"({"name":"verge","primitives":[{"attributes":{"POSITION":0},"indices":1,"material":1}]}])");
    test::write_file(file("m.gltf"), json);

    MeshLoadReport report;
    const TriangleMesh mesh = load_mesh(file("m.gltf"), report);
    ASSERT_EQ(mesh.triangles.size(), 6u);
    ASSERT_EQ(mesh.surfaces.size(), 6u);
    // No third: the default material assimp appends is used by no mesh here.
    ASSERT_EQ(report.materials.size(), 2u);
    EXPECT_EQ(report.materials[0], "asphalt");
    EXPECT_EQ(report.materials[1], "grass");
    // In node order: road, verge (10 m along x), road again.
    const std::vector<SurfaceId> expected{0, 0, 1, 1, 0, 0};
    EXPECT_EQ(mesh.surfaces, expected);
    const StaticCollider collider(mesh);
    for (std::uint32_t t = 0; t < 6; ++t) {
        const bool verge =
            triangle(mesh, t).vertices[0].x >= 10.0 && triangle(mesh, t).vertices[0].x < 20.0;
        EXPECT_EQ(collider.surface(t), verge ? 1 : 0) << t;
    }
}

TEST_F(MeshImport, GltfTriangleStripsBecomeTriangles) {
    // mode 5: a strip of 4 vertices is 2 triangles; the repeated index makes a degenerate.
    const std::vector<float> positions{0, 0, 0, 0, 0, -1, 1, 0, 0, 1, 0, -1};
    const std::vector<std::uint32_t> indices{0, 1, 2, 3, 3};
    test::write_gltf(file("s.gltf"), positions, indices, R"({"mesh":0})", "0", 5);
    MeshLoadReport report;
    load_mesh(file("s.gltf"), report);
    EXPECT_EQ(report.triangles, 2u);
    EXPECT_EQ(report.degenerate_dropped, 1u);
}

TEST_F(MeshImport, OtherFormatsLoadToo) {
    // ASCII STL, ASCII PLY and AC3D (the format of many racing-game tracks), one triangle each.
    test::write_file(file("a.stl"),
                     "solid t\nfacet normal 0 1 0\nouter loop\n"
                     "vertex 0 0 0\nvertex 1 0 0\nvertex 0 0 -1\n"
                     "endloop\nendfacet\nendsolid t\n");
    test::write_file(file("a.ply"),
                     "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
                     "property float y\nproperty float z\nelement face 1\n"
                     "property list uchar int vertex_indices\nend_header\n"
                     "0 0 0\n1 0 0\n0 0 -1\n3 0 1 2\n");
    test::write_file(file("a.ac"),
                     "AC3Db\nMATERIAL \"\" rgb 1 1 1 amb 0.2 0.2 0.2 emis 0 0 0 spec 0.5 0.5 0.5 "
                     "shi 10 trans 0\nOBJECT world\nkids 1\nOBJECT poly\nname \"road\"\n"
                     "numvert 3\n0 0 0\n1 0 0\n0 0 -1\nnumsurf 1\nSURF 0x10\nmat 0\nrefs 3\n"
                     "0 0 0\n1 0 0\n2 0 0\nkids 0\n");
    for (const char* name : {"a.stl", "a.ply", "a.ac"}) {
        MeshLoadReport report;
        const TriangleMesh mesh = load_mesh(file(name), report);
        ASSERT_EQ(mesh.triangles.size(), 1u) << name;
        EXPECT_DOUBLE_EQ(report.area, 0.5) << name;
        EXPECT_EQ(report.bounds.min, glm::dvec3(0, 0, -1)) << name;
        EXPECT_EQ(report.bounds.max, glm::dvec3(1, 0, 0)) << name;
    }
}

TEST_F(MeshImport, LoadingIsDeterministic) {
    test::write_file(file("r.obj"),
                     "v 0 0 0\nv 1 0 0\nv 0 0 -1\nv 1 0 -1\nv 2 0 0\n"
                     "f 1 2 3\nf 2 4 3\nf 2 5 4\n");
    const TriangleMesh a = load_mesh(file("r.obj"));
    const TriangleMesh b = load_mesh(file("r.obj"));
    EXPECT_EQ(a.vertices, b.vertices);
    EXPECT_EQ(a.triangles, b.triangles);
}

}  // namespace
}  // namespace trackphys
