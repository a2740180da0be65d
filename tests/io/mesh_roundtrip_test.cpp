// save_mesh then load_mesh gives back the same triangles, in every export format, and glTF
// their surface ids.

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include <glm/common.hpp>

#include "io_test_support.hpp"
#include "trackphys/geometry/triangle.hpp"
#include "trackphys/io/mesh_io.hpp"

namespace trackphys {
namespace {

namespace fs = std::filesystem;

// A height field of nx x nz quads split into two triangles each, counter-clockwise seen
// from above (+Y), every vertex shared by its neighbours.
TriangleMesh height_field(int nx, int nz, double spacing, const glm::dvec3& origin,
                          std::mt19937* jitter) {
    TriangleMesh mesh;
    std::uniform_real_distribution<double> noise(-0.3, 0.3);
    for (int k = 0; k <= nz; ++k)
        for (int i = 0; i <= nx; ++i) {
            glm::dvec3 p =
                origin + glm::dvec3(i * spacing, 0.25 * ((i * 7 + k * 3) % 5), -k * spacing);
            if (jitter != nullptr) {  // one draw per statement: argument order is unspecified
                p.x += noise(*jitter);
                p.y += noise(*jitter);
                p.z += noise(*jitter);
            }
            mesh.vertices.push_back(p);
        }
    const auto id = [nx](int i, int k) { return static_cast<std::uint32_t>(k * (nx + 1) + i); };
    for (int k = 0; k < nz; ++k)
        for (int i = 0; i < nx; ++i) {
            mesh.triangles.push_back({id(i, k), id(i + 1, k), id(i + 1, k + 1)});
            mesh.triangles.push_back({id(i, k), id(i + 1, k + 1), id(i, k + 1)});
        }
    return mesh;
}

double area(const TriangleMesh& mesh) {
    double sum = 0.0;
    for (const auto& t : mesh.triangles)
        sum += Triangle(mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]).area();
    return sum;
}

// x rounded to the nearest float32. The volatile is needed: GCC 12.2 at -O2 (SLP
// vectorizer) folds (double)(float)x back to x for two of three neighbouring components,
// wrong code that -fno-tree-slp-vectorize or clang avoid.
double through_float(double x) {
    volatile float f = static_cast<float>(x);
    return f;
}

// What the mesh becomes after one pass through float32 storage (mesh_io.hpp).
TriangleMesh rounded_to_float(TriangleMesh mesh) {
    for (glm::dvec3& p : mesh.vertices)
        p = glm::dvec3(through_float(p.x), through_float(p.y), through_float(p.z));
    return mesh;
}

// Whether each of loaded's triangles, found by its corners (sorted: STL and welding may
// rotate a triangle's), has mesh's surface id (kept) or 0.
void expect_surfaces(const TriangleMesh& mesh, const TriangleMesh& loaded, bool kept) {
    const auto ids_by_corners = [](const TriangleMesh& m) {
        std::vector<std::pair<std::vector<double>, SurfaceId>> ids;
        for (std::size_t t = 0; t < m.triangles.size(); ++t) {
            std::vector<std::vector<double>> corners;
            for (const std::uint32_t v : m.triangles[t])
                corners.push_back({m.vertices[v].x, m.vertices[v].y, m.vertices[v].z});
            std::sort(corners.begin(), corners.end());
            std::vector<double> key;
            for (const auto& c : corners) key.insert(key.end(), c.begin(), c.end());
            ids.push_back({key, m.surfaces.empty() ? SurfaceId{0} : m.surfaces[t]});
        }
        std::sort(ids.begin(), ids.end());
        return ids;
    };
    TriangleMesh expected = mesh;
    if (!kept) expected.surfaces.assign(mesh.triangles.size(), 0);
    EXPECT_EQ(ids_by_corners(loaded), ids_by_corners(expected));
}

class MeshRoundTrip : public test::ScratchFolderTest,
                      public ::testing::WithParamInterface<std::string> {};

TEST_P(MeshRoundTrip, FloatExactCoordinatesComeBackExactly) {
    // Multiples of 0.25 below 2^20: exactly representable in float32.
    const TriangleMesh mesh = height_field(6, 5, 1.25, {-3.0, 2.0, 4.0}, nullptr);
    const fs::path path = file("grid" + GetParam());
    save_mesh(mesh, path);

    MeshLoadReport report;
    const TriangleMesh loaded = load_mesh(path, report);
    EXPECT_TRUE(test::same_triangles(loaded, mesh));
    // Welding by position restores the shared vertices even where the format stores one
    // vertex per corner (STL).
    EXPECT_EQ(loaded.vertices.size(), mesh.vertices.size());
    EXPECT_EQ(report.triangles, mesh.triangles.size());
    EXPECT_EQ(report.vertices, mesh.vertices.size());
    EXPECT_EQ(report.degenerate_dropped, 0u);
    EXPECT_EQ(report.triangulation_lost, 0u);
    EXPECT_EQ(report.bounds.min, glm::dvec3(-3.0, 2.0, -2.25));
    EXPECT_EQ(report.bounds.max, glm::dvec3(4.5, 3.0, 4.0));
    EXPECT_NEAR(report.area, area(mesh), 1e-12 * area(mesh));
}

TEST_P(MeshRoundTrip, OtherCoordinatesComeBackRoundedToFloat) {
    // A jittered patch 5 km from the origin, where float32 spacing is about 0.5 mm.
    std::mt19937 rng(20261122);
    const TriangleMesh mesh = height_field(20, 10, 0.9, {5000.0, 120.0, -3000.0}, &rng);
    const fs::path path = file("far" + GetParam());
    save_mesh(mesh, path);

    const TriangleMesh loaded = load_mesh(path);
    const TriangleMesh expected = rounded_to_float(mesh);
    EXPECT_TRUE(test::same_triangles(loaded, expected));
    // And that rounding is small: at most half a float32 ulp at 5 km (2^12 <= x < 2^13).
    double worst = 0.0;
    for (std::size_t v = 0; v < mesh.vertices.size(); ++v) {
        const glm::dvec3 d = glm::abs(expected.vertices[v] - mesh.vertices[v]);
        worst = std::max({worst, d.x, d.y, d.z});
    }
    EXPECT_GT(worst, 0.0);
    EXPECT_LE(worst, std::ldexp(1.0, 12 - 24));
}

TEST_P(MeshRoundTrip, LeavesOnlyTheFilesOfTheFormat) {
    save_mesh(height_field(2, 2, 1.0, {0, 0, 0}, nullptr), file("m" + GetParam()));
    // Overwriting works the same way and leaves no temporary folder either.
    save_mesh(height_field(3, 2, 1.0, {0, 0, 0}, nullptr), file("m" + GetParam()));
    std::vector<std::string> expected{"m" + GetParam()};
    if (GetParam() == ".gltf") expected = {"m.bin", "m.gltf"};  // JSON + its buffer
    EXPECT_EQ(folder_listing(), expected);
    EXPECT_EQ(load_mesh(file("m" + GetParam())).triangles.size(), 12u);
}

// Surface ids come back from glTF (one material per id, the triangles grouped by id) when
// ids 0 to the highest all have triangles: each triangle, found by its corners, has its id
// again, materials named by id. The other formats, and glTF for ids with one unused in
// between (4 without 3: glTF would drop the unused material and shift 4), hold one surface.
TEST_P(MeshRoundTrip, SurfaceIdsComeBackFromGltfAlone) {
    for (const SurfaceId highest : {SurfaceId{3}, SurfaceId{4}}) {
        TriangleMesh mesh = height_field(6, 5, 1.25, {-3.0, 2.0, 4.0}, nullptr);
        for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
            mesh.surfaces.push_back(static_cast<SurfaceId>(t % 7 == 0 ? highest : t % 3));
        const fs::path path = file("surfaces" + std::to_string(highest) + GetParam());
        save_mesh(mesh, path);
        MeshLoadReport report;
        const TriangleMesh loaded = load_mesh(path, report);
        ASSERT_EQ(loaded.triangles.size(), mesh.triangles.size());
        const bool kept = (GetParam() == ".glb" || GetParam() == ".gltf") && highest == 3;
        expect_surfaces(mesh, loaded, kept);
        if (kept) {
            EXPECT_EQ(report.materials.size(), std::size_t(highest) + 1);
            for (int id = 0; id <= highest; ++id)
                EXPECT_EQ(report.materials.at(std::size_t(id)), "surface " + std::to_string(id));
        }
    }
}

INSTANTIATE_TEST_SUITE_P(Formats, MeshRoundTrip,
                         ::testing::Values(".glb", ".gltf", ".obj", ".ply", ".stl"),
                         [](const auto& format) { return format.param.substr(1); });

class MeshSave : public test::ScratchFolderTest {};

TEST_F(MeshSave, ExtensionIsCaseInsensitive) {
    const TriangleMesh mesh = height_field(1, 1, 1.0, {0, 0, 0}, nullptr);
    save_mesh(mesh, file("UPPER.GLB"));
    EXPECT_TRUE(test::same_triangles(load_mesh(file("UPPER.GLB")), mesh));
}

}  // namespace
}  // namespace trackphys
