// Bad input to load_mesh and save_mesh: a clear trackphys::Error, never a crash, never a
// partial output file.

#include <array>
#include <cstdint>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "io_test_support.hpp"
#include "trackphys/error.hpp"
#include "trackphys/io/mesh_io.hpp"

namespace trackphys {
namespace {

namespace fs = std::filesystem;

using test::load_error;

std::string save_error(const TriangleMesh& mesh, const fs::path& path) {
    try {
        save_mesh(mesh, path);
    } catch (const Error& e) {
        return e.what();
    }
    ADD_FAILURE() << "save_mesh(" << path << ") did not throw";
    return {};
}

TriangleMesh unit_square() {
    return {{{0, 0, 0}, {1, 0, 0}, {1, 0, -1}, {0, 0, -1}}, {{0, 1, 2}, {0, 2, 3}}};
}

std::string random_bytes(std::size_t size, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_int_distribution<int> byte(0, 255);
    std::string bytes(size, '\0');
    for (char& c : bytes) c = static_cast<char>(byte(rng));
    return bytes;
}

class MeshLoadErrors : public test::ScratchFolderTest {};

TEST_F(MeshLoadErrors, MissingFile) {
    const std::string message = load_error(file("nowhere.glb"));
    EXPECT_NE(message.find("nowhere.glb"), std::string::npos) << message;
    EXPECT_NE(message.find("no such file"), std::string::npos) << message;
}

TEST_F(MeshLoadErrors, FolderInsteadOfFile) {
    fs::create_directory(file("folder.obj"));
    const std::string message = load_error(file("folder.obj"));
    EXPECT_NE(message.find("not a regular file"), std::string::npos) << message;
}

TEST_F(MeshLoadErrors, EmptyFile) {
    for (const char* name : {"e.glb", "e.gltf", "e.obj", "e.ply", "e.stl", "e.fbx", "e"}) {
        test::write_file(file(name), "");
        const std::string message = load_error(file(name));
        EXPECT_NE(message.find(name), std::string::npos) << message;
        EXPECT_NE(message.find("empty"), std::string::npos) << message;
    }
}

TEST_F(MeshLoadErrors, GarbageBytes) {
    // Random bytes under every extension assimp might dispatch on, in three sizes.
    std::uint32_t seed = 1;
    for (const char* ext : {".glb", ".gltf", ".obj", ".ply", ".stl", ".fbx", ".ac", ".dae", ".3ds",
                            ".blend", ".x", ".off", ""})
        for (const std::size_t size : {std::size_t{7}, std::size_t{1000}, std::size_t{65536}}) {
            const fs::path path = file("garbage" + std::to_string(size) + ext);
            test::write_file(path, random_bytes(size, seed++));
            const std::string message = load_error(path);
            EXPECT_NE(message.find(path.filename().string()), std::string::npos) << message;
        }
}

TEST_F(MeshLoadErrors, GarbageAfterAValidLookingHeader) {
    // Magic bytes that send assimp straight to one reader, followed by random bytes.
    const std::vector<std::pair<std::string, std::string>> cases{
        {"h.glb", std::string("glTF\x02\x00\x00\x00\xff\xff\x00\x00", 12)},
        {"h.gltf", R"({"asset":{"version":"2.0"},"meshes":[{"primitives":[{"attributes":)"
                   R"({"POSITION":7}}]}],)"},
        // Claims a million vertices (12 MB) and holds a few hundred. assimp would allocate
        // what the header claims before it finds out, and leak that mesh on this error path
        // (assimp 5.2.5, issue #5717); load_mesh refuses the claim first (ply_header_check).
        {"h.ply",
         "ply\nformat binary_little_endian 1.0\nelement vertex 1000000\n"
         "property float x\nproperty float y\nproperty float z\nend_header\n"},
        {"h.stl", std::string(80, ' ') + std::string("\xff\xff\xff\x0f", 4)},
        {"h.obj", "v 1 2\nf 1 2 3 4 5 6 7 8 9\nf -9 -10 -11\n"},
        {"h.fbx", std::string("Kaydara FBX Binary  \x00\x1a\x00\xe8\x1c\x00\x00", 27)},
    };
    std::uint32_t seed = 100;
    for (const auto& [name, header] : cases) {
        test::write_file(file(name), header + random_bytes(4096, seed++));
        const std::string message = load_error(file(name));
        EXPECT_NE(message.find(name), std::string::npos) << message;
    }
}

TEST_F(MeshLoadErrors, PlyHeaderWithoutEndHeaderIsRejectedNotHung) {
    // assimp 5.2.5's PLY reader never returns on these (found by fuzz_mesh_import). The
    // strict header check refuses every line it does not know, and any control character
    // assimp would cut lines at. A timeout here is the bug.
    const std::string body =
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
        "property float y\nproperty float z\n";
    const std::vector<std::array<std::string, 3>> cases{
        {"bare.ply", "ply\nformat ascii 1.0\n", "line 2: the PLY header has no end_header line"},
        {"upper.ply", "PLY\nformat ascii 1.0\n", "line 1: a PLY file starts with a line 'ply'"},
        {"no_end.ply", body + "0 0 0\n1 0 0\n0 0 1\n", "line 7: unknown PLY header line '0'"},
        {"in_comment.ply", body + "comment end_header\n0 0 0\n", "line 8: unknown PLY header"},
        {"longer_token.ply", body + "end_headerX\n0 0 0\n",
         "line 7: unknown PLY header line 'end_headerX'"},
        {"vertical_tab.ply", body + "end_header\v0 0 0\n", "line 7: control character 11"},
        {"swallowed.ply", body + "comment a" + std::string(2, '\0') + "end_header\n0 0 0\n",
         "line 7: control character 0"},
        // A stray line in the header and end_header as the last bytes.
        {"ends_at_header.ply",
         "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nend_header",
         "line 5: the PLY file ends at its end_header line (no data)"},
        {"stray_line.ply", "ply\nformat ascii 1.0\nelement vertex 3\n0 0 0\nend_header\n",
         "line 4: unknown PLY header line '0'"},
    };
    for (const auto& [name, text, reason] : cases) {
        test::write_file(file(name), text);
        const std::string message = load_error(file(name));
        EXPECT_NE(message.find(name + "': " + reason), std::string::npos) << message;
    }
    // A header line with leading blanks or CR LF line ends still ends the header.
    for (const char* end : {"  end_header\n", "end_header\r\n"}) {
        test::write_file(file("ok.ply"), body +
                                             "element face 1\nproperty list uchar int "
                                             "vertex_indices\n" +
                                             end + "0 0 0\n1 0 0\n0 0 1\n3 0 1 2\n");
        EXPECT_EQ(load_mesh(file("ok.ply")).triangles.size(), 1u) << end;
    }
}

TEST_F(MeshLoadErrors, OnlyTheFormatsTrackphysReadsAreRead) {
    // assimp would take a PLY by content under these extensions, and read FBX, COLLADA,
    // DirectX and the rest with readers nothing bounds (issue 19).
    const std::string ply =
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
        "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
        "end_header\n0 0 0\n1 0 0\n0 0 1\n3 0 1 2\n";
    for (const char* name : {"as.xyz", "as.fbx", "as.dae", "as.x", "as.zae", "noextension"}) {
        test::write_file(file(name), ply);
        const std::string message = load_error(file(name));
        EXPECT_NE(message.find(std::string(name) + "': not a mesh format trackphys reads"),
                  std::string::npos)
            << message;
    }
    test::write_file(file("upper_case.PLY"), ply);
    EXPECT_EQ(load_mesh(file("upper_case.PLY")).triangles.size(), 1u);
}

TEST_F(MeshLoadErrors, OffCountsBeyondTheFileAreRejectedBeforeAllocating) {
    // assimp's OFF reader allocates the header's vertex and face counts before reading
    // (found by fuzz_mesh_import: "OFF" and thirty digits, tens of GB).
    const std::string digits(70, '6');
    const std::vector<std::array<std::string, 3>> cases{
        {"glued.off", "OFF" + digits + "\n5 2 0\n0 4 0\n1 0 0\n",
         "line 1: an OFF file starts with"},
        {"vertices.off", "OFF\n# a comment\n4000000000 1 0\n0 0 0\n",
         "line 3: OFF header claims 4000000000 vertices and 1 faces, more than the file's 37 "
         "bytes can hold"},
        {"faces.off", "COFF\n3 99999999 0\n0 0 0\n1 0 0\n0 0 1\n", "line 2: OFF header claims"},
        {"wraps.off", "OFF\n4294967299 1 0\n", "line 2: vertex count '4294967299' is not a count"},
        {"headerless.off", "\n3000000000 1 0\n0 0 0\n", "line 2: an OFF file starts with"},
    };
    for (const auto& [name, text, reason] : cases) {
        test::write_file(file(name), text);
        const std::string message = load_error(file(name));
        EXPECT_NE(message.find(name + "': " + reason), std::string::npos) << message;
    }
    // Counts the file can hold load.
    test::write_file(file("ok.off"),
                     "OFF\n# square\n4 2 0\n0 0 0\n1 0 0\n1 0 1\n0 0 1\n"
                     "3 0 1 2\n3 0 2 3\n");
    EXPECT_EQ(load_mesh(file("ok.off")).triangles.size(), 2u);
}

TEST_F(MeshLoadErrors, PlyElementCountBeyondTheFileIsRejectedBeforeAllocating) {
    // assimp allocates what the count claims before reading (found by fuzz_mesh_import: 45 GB
    // for a 400-byte file); each instance takes at least one byte of the file.
    test::write_file(file("claim.ply"),
                     "ply\nformat ascii 1.0\nelement vertex 100000000000"
                     "\nproperty float x\nproperty float y\n"
                     "property float z\nend_header\n0 0 0\n");
    EXPECT_NE(load_error(file("claim.ply"))
                  .find("claim.ply': line 3: element count '100000000000' is not a count from 0 "
                        "to 4294967295"),
              std::string::npos);
    test::write_file(file("bytes.ply"),
                     "ply\nformat binary_little_endian 1.0\nelement vertex "
                     "4000000000\nproperty float x\nend_header\n0000");
    EXPECT_NE(load_error(file("bytes.ply"))
                  .find("bytes.ply': PLY element 'vertex' claims 4000000000 instances, more than "
                        "the 4 bytes after the header can hold"),
              std::string::npos);
}

TEST_F(MeshLoadErrors, PlyFaceWithoutIndicesIsRejectedNotAborted) {
    // assimp's PLY reader keeps the face "0" and flags the mesh polygonal; its triangulation
    // then fails an ai_assert that aborts the process (assimp 5.2.5, found by
    // fuzz_mesh_import). A crash here is the bug.
    test::write_file(file("empty_face.ply"),
                     "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
                     "property float y\nproperty float z\nelement face 2\n"
                     "property list uchar int vertex_indices\nend_header\n"
                     "0 0 0\n1 0 0\n0 0 1\n3 0 1 2\n0\n");
    const std::string message = load_error(file("empty_face.ply"));
    EXPECT_NE(message.find("empty_face.ply': line 14: PLY element 'face' 1, property "
                           "'vertex_indices': a face of no vertex index"),
              std::string::npos)
        << message;
}

TEST_F(MeshLoadErrors, TruncatedGlb) {
    TriangleMesh mesh = unit_square();
    for (int i = 0; i < 50; ++i) {  // big enough that the binary chunk dominates the file
        mesh.vertices.push_back({i, 1.0, 0.0});
        mesh.triangles.push_back({0, 1, static_cast<std::uint32_t>(mesh.vertices.size() - 1)});
    }
    save_mesh(mesh, file("whole.glb"));
    const std::string whole = test::read_file(file("whole.glb"));
    ASSERT_GT(whole.size(), 200u);
    for (const std::size_t size : {whole.size() / 2, std::size_t{11}, std::size_t{12},
                                   std::size_t{20}, std::size_t{40}, whole.size() - 1}) {
        const fs::path cut = file("cut" + std::to_string(size) + ".glb");
        test::write_file(cut, whole.substr(0, size));
        const std::string message = load_error(cut);
        EXPECT_NE(message.find(cut.filename().string()), std::string::npos) << message;
    }
}

TEST_F(MeshLoadErrors, TruncatedBinaryPlyAndStl) {
    for (const char* name : {"whole.ply", "whole.stl"}) {
        save_mesh(unit_square(), file(name));
        const std::string whole = test::read_file(file(name));
        const fs::path cut = file(std::string("cut-") + name);
        test::write_file(cut, whole.substr(0, whole.size() - 10));
        const std::string message = load_error(cut);
        EXPECT_NE(message.find(cut.filename().string()), std::string::npos) << message;
    }
}

TEST_F(MeshLoadErrors, NonFiniteObjCoordinatesNameFileMeshAndVertex) {
    const std::vector<std::string> bad{"nan", "-nan", "inf", "-inf", "1e999"};
    for (std::size_t i = 0; i < bad.size(); ++i) {
        const std::string name = "bad" + std::to_string(i) + ".obj";
        test::write_file(file(name), "o road\nv 0 0 0\nv 1 0 0\nv 0 0 -1\nv 1 " + bad[i] +
                                         " -1\nf 1 2 3\nf 2 4 3\n");
        const std::string message = load_error(file(name));
        EXPECT_NE(message.find(name), std::string::npos) << message;
        EXPECT_NE(message.find("mesh 'road'"), std::string::npos) << message;
        // assimp's OBJ reader numbers vertices per face corner: corner 2 of face 2 is vertex 4.
        EXPECT_NE(message.find("vertex 4 "), std::string::npos) << message;
        EXPECT_NE(message.find("non-finite"), std::string::npos) << message;
    }
}

TEST_F(MeshLoadErrors, NanInAGltfBufferNamesMeshAndVertex) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    test::write_gltf(file("nan.gltf"), {0, 0, 0, 1, 0, 0, 0, nan, -1}, {0, 1, 2}, R"({"mesh":0})",
                     "0");
    const std::string message = load_error(file("nan.gltf"));
    EXPECT_NE(message.find("nan.gltf"), std::string::npos) << message;
    EXPECT_NE(message.find("mesh 'road', vertex 2 has a non-finite coordinate"), std::string::npos)
        << message;
}

TEST_F(MeshLoadErrors, NodeTransformsThatOverflowNameTheNode) {
    // Every number in the file is a finite float, but eight nested scales of 1e38 take the
    // vertex at x = 3e38 beyond double's range once the transforms are composed.
    std::string nodes;
    for (int i = 0; i < 8; ++i)
        nodes += R"({"name":"n)" + std::to_string(i) + R"(","scale":[1e38,1,1],)" +
                 (i < 7 ? R"("children":[)" + std::to_string(i + 1) + "]}," : R"("mesh":0})");
    test::write_gltf(file("big.gltf"), {0, 0, 0, 3e38f, 0, 0, 0, 0, -1}, {0, 1, 2}, nodes, "0");
    const std::string message = load_error(file("big.gltf"));
    EXPECT_NE(message.find("big.gltf"), std::string::npos) << message;
    EXPECT_NE(message.find("mesh 'road', vertex 1 is non-finite once placed by node 'n7'"),
              std::string::npos)
        << message;
}

TEST_F(MeshLoadErrors, NoTriangles) {
    // Only points and lines; only degenerate triangles; vertices but no faces; a glTF
    // scene without meshes.
    test::write_file(file("lines.obj"), "v 0 0 0\nv 1 0 0\nv 2 2 2\nl 1 2 3\np 1 2 3\n");
    test::write_file(file("flat.obj"), "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\nf 1 1 1\n");
    test::write_file(file("cloud.obj"), "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 3 3 3\n# no faces\n");
    test::write_file(file("nothing.gltf"),
                     R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],)"
                     R"("nodes":[{"name":"empty"}]})");
    for (const char* name : {"lines.obj", "flat.obj", "cloud.obj", "nothing.gltf"}) {
        const std::string message = load_error(file(name));
        EXPECT_NE(message.find(name), std::string::npos) << message;
    }
    const std::string lines = load_error(file("lines.obj"));
    EXPECT_NE(lines.find("contains no triangles (0 degenerate dropped, 3 points and 2 lines"),
              std::string::npos)
        << lines;
    const std::string flat = load_error(file("flat.obj"));
    EXPECT_NE(flat.find("no triangles (2 degenerate dropped"), std::string::npos) << flat;
}

TEST_F(MeshLoadErrors, ObjIndexOutOfRange) {
    test::write_file(file("idx.obj"), "v 0 0 0\nv 1 0 0\nv 0 0 -1\nf 1 2 99\n");
    const std::string message = load_error(file("idx.obj"));
    EXPECT_NE(message.find("idx.obj"), std::string::npos) << message;
}

class MeshSaveErrors : public test::ScratchFolderTest {};

TEST_F(MeshSaveErrors, UnsupportedExtensionCreatesNothing) {
    for (const char* name : {"t.xyz", "t", "t.fbx", "t.glb.tmp"}) {
        const std::string message = save_error(unit_square(), file(name));
        EXPECT_NE(message.find(name), std::string::npos) << message;
        EXPECT_NE(message.find("unknown extension"), std::string::npos) << message;
    }
    EXPECT_TRUE(folder_listing().empty());
}

TEST_F(MeshSaveErrors, InvalidMeshCreatesNothing) {
    TriangleMesh empty;
    TriangleMesh bad_index = unit_square();
    bad_index.triangles.push_back({0, 1, 4});
    TriangleMesh nan = unit_square();
    nan.vertices[2].y = std::numeric_limits<double>::quiet_NaN();
    TriangleMesh huge = unit_square();
    huge.vertices[1].x = 1e39;  // finite in double, infinite in float32
    EXPECT_NE(save_error(empty, file("a.glb")).find("no triangles"), std::string::npos);
    EXPECT_NE(save_error(bad_index, file("a.glb")).find("triangle 2 refers to missing vertex 4"),
              std::string::npos);
    EXPECT_NE(save_error(nan, file("a.obj")).find("vertex 2 is not finite"), std::string::npos);
    EXPECT_NE(save_error(huge, file("a.ply")).find("vertex 1 lies beyond float32 range"),
              std::string::npos);
    EXPECT_TRUE(folder_listing().empty());
}

TEST_F(MeshSaveErrors, FailingSaveLeavesAnExistingFileUntouched) {
    save_mesh(unit_square(), file("keep.glb"));
    const std::string before = test::read_file(file("keep.glb"));
    save_error(TriangleMesh{}, file("keep.glb"));
    EXPECT_EQ(test::read_file(file("keep.glb")), before);
    EXPECT_EQ(folder_listing(), std::vector<std::string>{"keep.glb"});
}

TEST_F(MeshSaveErrors, FailureAfterExportLeavesNoPartialFile) {
    // The export itself succeeds, then the final rename fails because a non-empty folder
    // has the destination's name: the staged file and folder must both disappear.
    fs::create_directories(file("taken.obj") / "inside");
    const std::string message = save_error(unit_square(), file("taken.obj"));
    EXPECT_NE(message.find("taken.obj"), std::string::npos) << message;
    EXPECT_EQ(folder_listing(), std::vector<std::string>{"taken.obj"});
    EXPECT_TRUE(fs::is_directory(file("taken.obj") / "inside"));

    // The same for a .gltf, whose .bin companion is renamed into place first.
    fs::create_directories(file("taken.gltf") / "inside");
    save_error(unit_square(), file("taken.gltf"));
    EXPECT_EQ(folder_listing(), (std::vector<std::string>{"taken.gltf", "taken.obj"}));
}

TEST_F(MeshSaveErrors, MissingDestinationFolder) {
    const std::string message = save_error(unit_square(), file("no/such/folder/t.glb"));
    EXPECT_NE(message.find("t.glb"), std::string::npos) << message;
    EXPECT_TRUE(folder_listing().empty());
}

}  // namespace
}  // namespace trackphys
