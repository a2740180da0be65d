// The strict checks in front of assimp's readers (src/io/mesh_checks.hpp, issue 19): what a
// malformed file is refused with, naming the file and the place, before any reader allocates.

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "io_test_support.hpp"
#include "trackphys/io/mesh_io.hpp"

namespace trackphys {
namespace {

namespace fs = std::filesystem;

using Case = std::array<std::string, 3>;  // file name, content, expected reason

class MeshChecks : public test::ScratchFolderTest {
  protected:
    void expect_refused(const std::vector<Case>& cases) {
        for (const auto& [name, text, reason] : cases) {
            test::write_file(file(name), text);
            const std::string message = test::load_error(file(name));
            EXPECT_NE(message.find(name + "': "), std::string::npos) << message;
            EXPECT_NE(message.find(reason), std::string::npos)
                << "expected: " << reason << "\n got: " << message;
        }
    }
};

const std::string kPlyVertices =
    "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
    "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
    "0 0 0\n1 0 0\n0 0 1\n";

TEST_F(MeshChecks, PlyCountsAndIndices) {
    expect_refused({
        {"wraps.ply", "ply\nformat ascii 1.0\nelement vertex 4294967299\nproperty float x\n",
         "line 3: element count '4294967299' is not a count from 0 to 4294967295"},
        {"trailing.ply", "ply\nformat ascii 1.0\nelement vertex 3x\nproperty float x\n",
         "line 3: element count '3x' is not a count"},
        {"list_too_big.ply", kPlyVertices + "300 0 1 2\n",
         "line 13: PLY element 'face' 0, property 'vertex_indices' count: 300 does not fit its "
         "type 'uchar'"},
        {"forty_digits.ply", kPlyVertices + std::string(40, '9') + " 0 1 2\n",
         "line 13: PLY element 'face' 0, property 'vertex_indices' count '" + std::string(40, '9') +
             "' is not an integer"},
        {"index_high.ply", kPlyVertices + "3 0 1 3\n",
         "line 13: PLY element 'face' 0, property 'vertex_indices': vertex index 3 out of range "
         "(3 vertices)"},
        {"index_negative.ply", kPlyVertices + "3 0 -1 2\n", "vertex index -1 out of range"},
        {"short_list.ply", kPlyVertices + "3 0 1\n", "the list claims 3 items, the line holds 2"},
        {"truncated.ply", kPlyVertices.substr(0, kPlyVertices.size() - 6),
         "line 11: the file ends before PLY element 'vertex' 2"},
        {"extra.ply", kPlyVertices + "3 0 1 2 7\n", "line 13: more values than PLY element 'face'"},
        {"bad_number.ply",
         "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nend_header\n1.5.2\n",
         "line 6: PLY element 'vertex' 0, property 'x' '1.5.2' is not a number"},
        {"no_properties.ply",
         "ply\nformat ascii 1.0\nelement vertex 9\nend_header\n\n\n\n\n\n\n\n\n\n",
         "PLY element 'vertex' claims 9 instances but has no properties"},
    });
}

TEST_F(MeshChecks, BinaryPlyIsWalkedToItsEnd) {
    const std::string header =
        "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
        "property float y\nproperty float z\nelement face 1\n"
        "property list uchar uint vertex_indices\nend_header\n";
    const std::string vertices(36, '\0');
    const std::string face =
        std::string("\x03\x00\x00\x00\x00\x01\x00\x00\x00\x02\x00\x00\x00", 13);
    std::string high = face;
    high[9] = '\x07';
    expect_refused({
        {"cut.ply", header + vertices + face.substr(0, 7),
         "byte 211, PLY element 'face' 0, property 'vertex_indices': the list of 3 items runs "
         "past the file"},
        {"high.ply", header + vertices + high,
         "PLY element 'face' 0, property 'vertex_indices': vertex index 7 out of range"},
        {"crlf.ply",
         "ply\r\nformat binary_little_endian 1.0\r\nelement vertex 1\r\nproperty float "
         "x\r\nend_header\r\n0000",
         "a binary PLY header's end_header line ends in"},
    });
}

TEST_F(MeshChecks, StlOfNeitherKind) {
    const std::string facet =
        "facet normal 0 1 0\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 0 1\nendloop\n"
        "endfacet\n";
    expect_refused({
        {"garbage.stl", "hello",
         "not a binary STL (its size is not 84 + 50 x the triangle count at byte 80), and as "
         "ASCII STL: line 1: expected 'solid'"},
        {"four.stl",
         "solid a\nfacet normal 0 1 0\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
         "vertex 0 0 1\nvertex 1 1 1\nendloop\nendfacet\nendsolid a\n",
         "line 7: expected 'endloop', found 'vertex'"},
        {"unended.stl", "solid a\n" + facet, "the file ends before 'endsolid'"},
        {"nan_word.stl", "solid a\nfacet normal 0 1 0\nouter loop\nvertex 0 0 x\n",
         "line 4: vertex 'x' is not a number"},
        // A binary STL whose count claims more triangles than its size holds is no binary STL.
        {"claims.stl", std::string(80, ' ') + "zzzz" + std::string(50, 'a'),
         "and as ASCII STL: line 1: expected 'solid'"},
    });
}

TEST_F(MeshChecks, GltfReferencesStayInTheMeshFolder) {
    const auto gltf = [](const std::string& uri) {
        return R"({"asset":{"version":"2.0"},"buffers":[{"uri":")" + uri +
               R"(","byteLength":36}]})";
    };
    fs::create_directories(file("sub"));
    test::write_file(file("sub/inside.bin"), std::string(36, '\0'));
    expect_refused({
        {"absolute.gltf", gltf("/etc/passwd"),
         "glTF buffers[0].uri: the reference '/etc/passwd' is "
         "an absolute path"},
        {"escapes.gltf", gltf("../../../../etc/passwd"), "leaves the mesh's folder"},
        {"escapes_later.gltf", gltf("sub/../../x.bin"), "leaves the mesh's folder"},
        {"file_url.gltf", gltf("file:///etc/passwd"),
         "the reference 'file:///etc/passwd' is a URL"},
        {"http.gltf", gltf("http://example.com/a.bin"), "is a URL"},
        {"backslash.gltf", gltf("..\\\\x.bin"), "uses '\\'"},
        {"missing.gltf", gltf("nowhere.bin"), "the reference 'nowhere.bin' is no file"},
        {"data_plain.gltf", gltf("data:,abc"), "a malformed data: URI"},
        {"data_bad_char.gltf", gltf("data:application/octet-stream;base64,AA*A"),
         "a data: URI with a character outside base64"},
        {"data_short.gltf", gltf("data:application/octet-stream;base64,AAAA"),
         "glTF buffers[0]: byteLength 36 but only 3 bytes hold it"},
        {"inside_short.gltf",
         R"({"asset":{"version":"2.0"},"buffers":[{"uri":"sub/inside.bin","byteLength":37}]})",
         "byteLength 37 but only 36 bytes hold it"},
    });
    // A symbolic link beside the mesh is followed only to a file in its folder: a folder of
    // downloaded files must not make it read anything else the user can.
    fs::create_directories(file("elsewhere"));
    test::write_file(file("elsewhere/secret.bin"), std::string(36, '\0'));
    fs::create_directories(file("mesh/sub"));
    test::write_file(file("mesh/sub/inside.bin"), std::string(36, '\0'));
    fs::create_symlink(file("elsewhere/secret.bin"), file("mesh/secret.bin"));
    fs::create_symlink(file("elsewhere"), file("mesh/linked_folder"));
    fs::create_symlink(file("mesh/sub/inside.bin"), file("mesh/inside.bin"));
    expect_refused({
        {"mesh/out.gltf", gltf("secret.bin"),
         "the reference 'secret.bin' leads out of the mesh's folder through a symbolic link"},
        {"mesh/out_folder.gltf", gltf("linked_folder/secret.bin"), "through a symbolic link"},
    });
    test::write_file(file("mesh/in.gltf"), gltf("inside.bin"));
    EXPECT_EQ(test::load_error(file("mesh/in.gltf")).find("symbolic link"), std::string::npos);
}

TEST_F(MeshChecks, GltfAccessorsAndNodes) {
    const auto gltf = [](const std::string& accessor, const std::string& nodes) {
        return R"({"asset":{"version":"2.0"},"buffers":[{"uri":"data:application/octet-stream;base64,)" +
               std::string(48, 'A') +
               R"(","byteLength":36}],"bufferViews":[{"buffer":0,"byteLength":36}],"accessors":[)" +
               accessor + R"(],"nodes":[)" + nodes + "]}";
    };
    // The document with one more member, e.g. R"("skins":[])".
    const auto with = [](std::string doc, const std::string& member) {
        return doc.insert(doc.size() - 1, "," + member);
    };
    const std::string ok = R"({"bufferView":0,"componentType":5126,"count":3,"type":"VEC3"})";
    std::string deep = R"({"children":[1]})";
    for (int n = 1; n < 100; ++n)
        deep += n == 99 ? ",{}" : R"(,{"children":[)" + std::to_string(n + 1) + "]}";
    expect_refused({
        {"count.gltf", gltf(R"({"bufferView":0,"componentType":5126,"count":4,"type":"VEC3"})", ""),
         "glTF accessors[0]: 4 elements of 12 bytes every 12 from byte 0 run past its buffer "
         "view's 36 bytes"},
        {"huge.gltf",
         gltf(R"({"bufferView":0,"componentType":5126,"count":1e20,"type":"VEC3"})", ""),
         "not a non-negative integer"},
        {"sparse.gltf",
         gltf(R"({"componentType":5126,"count":3,"type":"VEC3","sparse":{"count":1}})", ""),
         "glTF accessors[0]: a sparse accessor"},
        {"cycle.gltf", gltf(ok, R"({"children":[1]},{"children":[0]})"), "children form a cycle"},
        {"two_parents.gltf", gltf(ok, R"({"children":[2]},{"children":[2]},{})"),
         "has two parents"},
        {"deep.gltf", gltf(ok, deep), "nested deeper than 64"},
        {"json_deep.gltf", std::string(100, '[') + std::string(100, ']'),
         "glTF JSON nested deeper than 64"},
        {"overlapping.gltf",
         R"({"asset":{"version":"2.0"},"buffers":[{"uri":"data:application/octet-stream;base64,)" +
             std::string(48, 'A') +
             R"(","byteLength":36}],"bufferViews":[{"buffer":0,"byteLength":36,"byteStride":4}],)"
             R"("accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3"}]})",
         "glTF accessors[0]: elements of 12 bytes overlap in its buffer view's stride of 4"},
        // assimp reads a skin's matrices without looking: none crashed it, too few it read
        // past.
        {"skin_without_matrices.gltf",
         with(gltf(ok, R"({"skin":0})"), R"("skins":[{"joints":[0]}])"),
         "glTF skins[0]: no inverseBindMatrices"},
        {"skin_short_of_matrices.gltf",
         with(gltf(ok, R"({"skin":0},{})"),
              R"("skins":[{"joints":[0,1],"inverseBindMatrices":0}])"),
         "glTF skins[0].inverseBindMatrices: not a float MAT4 for each of its 2 joints"},
        // What the importer reads as glTF does not mean it, or not at all.
        {"gpu_instances.gltf", gltf(ok, R"({"extensions":{"EXT_mesh_gpu_instancing":{}}})"),
         "glTF nodes[0]: EXT_mesh_gpu_instancing: its instances are not read"},
        {"draco.gltf", with(gltf(ok, ""), R"("extensionsRequired":["KHR_draco_mesh_compression"])"),
         "glTF extensionsRequired[0]: 'KHR_draco_mesh_compression' may change the geometry"},
        {"rotation_not_unit.gltf", gltf(ok, R"({"rotation":[10,0,0,0]})"),
         "glTF nodes[0].rotation: not a unit quaternion"},
        // Length^2 1.0008: a 5 km track 2 m longer.
        {"rotation_slightly_long.gltf", gltf(ok, R"({"rotation":[0,0.7074,0,0.7074]})"),
         "glTF nodes[0].rotation: not a unit quaternion"},
        {"projective.gltf", gltf(ok, R"({"matrix":[1,0,0,0,0,1,0,0,0,0,1,0,0,0,0,0]})"),
         "glTF nodes[0].matrix: not an affine transform"},
        {"positions_vec2.gltf",
         with(gltf(R"({"bufferView":0,"componentType":5126,"count":3,"type":"VEC2"})", ""),
              R"("meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}])"),
         "glTF meshes[0].primitives[0].attributes.POSITION: not an accessor of float VEC3"},
        {"partial_triangle.gltf",
         with(gltf(R"({"bufferView":0,"componentType":5126,"count":2,"type":"VEC3"})", ""),
              R"("meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}])"),
         "glTF meshes[0].primitives[0]: 2 vertices without indices, not whole triangles"},
        {"float_indices.gltf",
         with(gltf(ok, ""),
              R"("meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":0}]}])"),
         "glTF meshes[0].primitives[0].indices: not an accessor of unsigned integers"},
        {"four_indices.gltf",
         with(gltf(ok + R"(,{"bufferView":0,"componentType":5125,"count":4,"type":"SCALAR"})", ""),
              R"("meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1}]}])"),
         "glTF meshes[0].primitives[0].indices: 4 indices, not whole triangles"},
        {"glb_length.glb",
         std::string("glTF\x02\x00\x00\x00\xff\xff\x00\x00", 12) + std::string(20, ' '),
         "byte 8: the GLB header's length 65535 is not the file's 32"},
    });
    // What real exporters require and the importer reads as meant: three.js's GLTFExporter
    // requires quantization for Int16 normals and EXT_texture_webp for WebP textures.
    for (const char* harmless :
         {"KHR_mesh_quantization", "EXT_texture_webp", "KHR_materials_variants"}) {
        test::write_file(
            file("harmless.gltf"),
            with(gltf(ok, ""), std::string(R"("extensionsRequired":[")") + harmless + R"("])"));
        EXPECT_EQ(test::load_error(file("harmless.gltf")).find("extensionsRequired"),
                  std::string::npos)
            << harmless;
    }
}

TEST_F(MeshChecks, ObjIndicesAndStatements) {
    const std::string square = "v 0 0 0\nv 1 0 0\nv 1 0 1\nv 0 0 1\nvt 0 0\nvn 0 1 0\n";
    expect_refused({
        {"high.obj", square + "f 1 2 5\n",
         "line 7: vertex index 5 out of range (4 defined so far)"},
        {"negative.obj", square + "f -1 -2 -5\n", "line 7: vertex index -5 out of range"},
        {"zero.obj", square + "f 0 1 2\n", "line 7: vertex index 0 out of range"},
        {"before.obj", "f 1 2 3\n" + square, "line 1: vertex index 1 out of range (0 defined"},
        {"uv.obj", square + "f 1/2 2/1 3/1\n", "line 7: texture coordinate index 2 out of range"},
        {"normal.obj", square + "f 1//2 2//1 3//1\n", "line 7: normal index 2 out of range"},
        {"wraps.obj", square + "f 1 2 4294967297\n", "vertex index 4294967297 out of range"},
        {"trailing.obj", square + "f 1 2 3x\n", "line 7: vertex index '3x' is not an integer"},
        {"two.obj", square + "f 1 2\n", "line 7: a face of fewer than 3 corners"},
        {"word.obj", square + "v 1 2 z\n", "line 7: a vertex 'z' is not a number"},
        {"unknown.obj", "hello world\n", "line 1: the statement 'hello' is not read"},
        {"curve.obj", square + "curv 0 1 1 2\n", "the statement 'curv' is not read"},
        {"continued.obj", square + "f 1 2 \\\n3\n", "a line continued with"},
    });
}

TEST_F(MeshChecks, Ac3dCountsIndicesAndNesting) {
    const std::string head =
        "AC3Db\nMATERIAL \"\" rgb 1 1 1 amb 1 1 1 emis 0 0 0 spec 0 0 0 shi 1 trans 0\n"
        "OBJECT world\nkids 1\nOBJECT poly\nnumvert 3\n0 0 0\n1 0 0\n0 0 1\n";
    const auto surface = [](const std::string& flags, const std::string& refs) {
        return "numsurf 1\nSURF " + flags + "\nmat 0\nrefs " + refs + "\nkids 0\n";
    };
    std::string deep = "AC3Db\n";
    for (int level = 0; level < 70; ++level) deep += "OBJECT group\nkids 1\n";
    expect_refused({
        {"strip.ac", head + surface("0x14", "1\n0 0 0"),
         "line 13: a triangle strip of 1 references (at least 3)"},
        {"index.ac", head + surface("0x10", "3\n0 0 0\n1 0 0\n3 0 0"),
         "line 16: vertex index 3 out of range (3 vertices)"},
        {"type.ac", head + surface("0x13", "3\n0 0 0\n1 0 0\n2 0 0"), "unknown surface type 3"},
        {"flags.ac", head + surface("16", "3\n0 0 0\n1 0 0\n2 0 0"), "are not hexadecimal"},
        {"numvert.ac", "AC3Db\nOBJECT poly\nnumvert 99999999\n0 0 0\n",
         "line 3: vertex count '99999999' is not a count from 0 to"},
        {"truncated.ac", head.substr(0, head.size() - 4),
         "line 9: vertex 2 has 1 numbers, not 3 (or 6 with a normal)"},
        {"deep.ac", deep, "objects nested deeper than 64"},
        {"data.ac", "AC3Db\nOBJECT poly\ndata 500\nab\n", "line 3: data runs past the file"},
        {"unknown.ac", "AC3Db\nOBJECT poly\nbogus 1\n", "unknown AC3D object line 'bogus'"},
    });
}

TEST_F(MeshChecks, Ac3dStripThatWrapsAssimpsFaceCountIsRefused) {
    // The heap corruption of issue 19: assimp 5.2.5 counts a strip's faces as refs - 2 in
    // unsigned arithmetic, so a strip of one reference subtracts one from its mesh's face
    // count; with two triangles before it, it allocates one face and writes two (valgrind:
    // "Invalid write of size 4 ... 0 bytes after a block of size 24"). Also a seed of
    // fuzz_mesh_import (ac3d_strip_wraps_face_count.ac.seed).
    test::write_file(file("strip.ac"), test::read_file(fs::path(TRACKPHYS_FUZZ_SEEDS_DIR) /
                                                       "ac3d_strip_wraps_face_count.ac.seed")
                                           .substr(1));
    EXPECT_NE(test::load_error(file("strip.ac"))
                  .find("strip.ac': line 27: a triangle strip of 1 references (at least 3)"),
              std::string::npos);
}

TEST_F(MeshChecks, PlySecondVertexElementIsRefused) {
    // Found by fuzz_mesh_import (issue 19, 30-minute runs): assimp 5.2.5 sizes the vertex
    // array by the first 'element vertex' and writes a second one's instances into it, past
    // its end (valgrind: "Invalid write of size 8 ... 0 bytes after a block of size 36" for
    // 3 then 10 vertices). Also a seed of fuzz_mesh_import.
    test::write_file(file("twice.ply"), test::read_file(fs::path(TRACKPHYS_FUZZ_SEEDS_DIR) /
                                                        "ply_second_vertex_element.ply.seed")
                                            .substr(1));
    EXPECT_NE(
        test::load_error(file("twice.ply")).find("twice.ply': line 7: a second element 'vertex'"),
        std::string::npos);
    // Faces and triangle strips share that array the same way.
    const std::string strips = "element tristrips 1\nproperty list int int vertex_indices\n";
    std::string both = kPlyVertices;
    both.insert(both.find("element face"), strips);
    expect_refused({{"both.ply", both + "3 0 1 2\n",
                     "line 9: an element 'face' besides 'tristrips' (faces or triangle strips, "
                     "not both)"}});
}

}  // namespace
}  // namespace trackphys
