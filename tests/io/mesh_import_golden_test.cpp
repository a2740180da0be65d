// Valid files of every format load bit for bit as they did before import was bounded
// (issue 19): make_valid_meshes.py writes them, and mesh_import_golden.txt holds what the
// loader of that time returned for each (its report and a hash of every vertex and index;
// binary.glb, external.gltf and nested.ac recorded again once duplicate triangles were
// dropped, and the count of duplicates added to every line).
// Run with TRACKPHYS_RECORD_MESH_GOLDEN=1 to rewrite that file from the loader as it is,
// which is only right when a change of output is intended and explained in its commit.

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "core/fnv1a.hpp"
#include "io/io_test_support.hpp"
#include "trackphys/io/mesh_io.hpp"

namespace trackphys {
namespace {

namespace fs = std::filesystem;

const fs::path kGolden = fs::path(TRACKPHYS_TESTS_IO_DIR) / "mesh_import_golden.txt";
const fs::path kGenerator = fs::path(TRACKPHYS_TESTS_IO_DIR) / "make_valid_meshes.py";

// One line per file: what load_mesh reports and a hash of the mesh's bits.
std::string summary(const TriangleMesh& mesh, const MeshLoadReport& r) {
    core::Fnv1a hash;
    for (const glm::dvec3& v : mesh.vertices) hash.add(v);
    for (const auto& t : mesh.triangles) hash.add(t.data(), sizeof t);
    std::ostringstream out;
    out << "triangles " << r.triangles << " vertices " << r.vertices << " instances "
        << r.mesh_instances << " degenerate " << r.degenerate_dropped << " duplicates "
        << r.duplicates_dropped << " points " << r.points_skipped << " lines " << r.lines_skipped
        << " lost " << r.triangulation_lost << " mirrored " << r.mirrored_instances << " hash "
        << std::hex << hash.value;
    return out.str();
}

std::map<std::string, std::string> read_golden() {
    std::map<std::string, std::string> lines;
    std::ifstream in(kGolden);
    std::string name, rest;
    while (in >> name && std::getline(in, rest)) lines[name] = rest.substr(1);
    return lines;
}

class MeshImportGolden : public test::ScratchFolderTest {};

TEST_F(MeshImportGolden, ValidFilesLoadAsBeforeImportWasBounded) {
    const std::string command =
        std::string(TRACKPHYS_PYTHON) + " " + kGenerator.string() + " " + folder_.string();
    ASSERT_EQ(std::system(command.c_str()), 0) << command;

    std::map<std::string, std::string> loaded;
    for (const fs::directory_entry& e : fs::directory_iterator(folder_)) {
        if (e.path().extension() == ".bin") continue;  // a .gltf's buffer, not a mesh
        MeshLoadReport report;
        const TriangleMesh mesh = load_mesh(e.path(), report);
        loaded[e.path().filename().string()] = summary(mesh, report);
    }

    if (std::getenv("TRACKPHYS_RECORD_MESH_GOLDEN") != nullptr) {
        std::ofstream out(kGolden);
        for (const auto& [name, line] : loaded) out << name << ' ' << line << '\n';
        GTEST_SKIP() << "recorded " << kGolden;
    }
    const std::map<std::string, std::string> expected = read_golden();
    ASSERT_GE(expected.size(), 15u) << "too few files in " << kGolden;
    for (const auto& [name, line] : expected) {
        ASSERT_TRUE(loaded.count(name)) << name << " was not generated";
        EXPECT_EQ(loaded[name], line) << name;
    }
    EXPECT_EQ(loaded.size(), expected.size()) << "files the golden list does not know";
}

}  // namespace
}  // namespace trackphys
