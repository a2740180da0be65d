#pragma once

// Shared by the io tests: a scratch folder per test, file writers, and a comparison of
// meshes that ignores vertex order, welding and which corner a triangle starts at.

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>
#include <vector>

#include <gtest/gtest.h>

#include "trackphys/error.hpp"
#include "trackphys/geometry/triangle_mesh.hpp"
#include "trackphys/io/mesh_io.hpp"

namespace trackphys::test {

namespace fs = std::filesystem;

/// A fresh, empty folder for each test, removed with everything in it afterwards.
class ScratchFolderTest : public ::testing::Test {
  protected:
    void SetUp() override {
        std::string pattern = (fs::temp_directory_path() / "trackphys-io-XXXXXX").string();
        ASSERT_NE(::mkdtemp(pattern.data()), nullptr);
        folder_ = pattern;
    }
    void TearDown() override {
        std::error_code ignored;
        fs::remove_all(folder_, ignored);
    }

    fs::path file(const std::string& name) const { return folder_ / name; }

    /// The names in the scratch folder, sorted: shows leftovers of a failed save.
    std::vector<std::string> folder_listing() const {
        std::vector<std::string> names;
        for (const fs::directory_entry& e : fs::directory_iterator(folder_))
            names.push_back(e.path().filename().string());
        std::sort(names.begin(), names.end());
        return names;
    }

    fs::path folder_;
};

/// The message load_mesh throws for path (fails the test when nothing is thrown).
inline std::string load_error(const fs::path& path) {
    try {
        load_mesh(path);
    } catch (const Error& e) {
        return e.what();
    }
    ADD_FAILURE() << "load_mesh(" << path << ") did not throw";
    return {};
}

inline void write_file(const fs::path& path, std::string_view bytes) {
    std::ofstream out(path, std::ios::binary);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    ASSERT_TRUE(out.good()) << path;
}

inline std::string read_file(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

using Corner = std::array<double, 3>;
using CornerTriple = std::array<Corner, 3>;

/// Each triangle as its three corner positions, rotated (winding kept) to start at its
/// lexicographically smallest corner, then sorted: equal for two meshes exactly when they
/// hold the same triangles with the same winding, whatever their vertex numbering.
inline std::vector<CornerTriple> triangle_set(const TriangleMesh& mesh) {
    std::vector<CornerTriple> set;
    set.reserve(mesh.triangles.size());
    for (const auto& t : mesh.triangles) {
        CornerTriple c;
        for (std::size_t k = 0; k < 3; ++k) {
            const glm::dvec3& p = mesh.vertices[t[k]];
            c[k] = {p.x, p.y, p.z};
        }
        const auto first = std::min_element(c.begin(), c.end()) - c.begin();
        std::rotate(c.begin(), c.begin() + first, c.end());
        set.push_back(c);
    }
    std::sort(set.begin(), set.end());
    return set;
}

/// Whether a and b hold the same triangles (triangle_set); on failure the message shows the
/// counts and the first differing triangle in full precision, not two pages of numbers.
inline ::testing::AssertionResult same_triangles(const TriangleMesh& a, const TriangleMesh& b) {
    const std::vector<CornerTriple> sa = triangle_set(a);
    const std::vector<CornerTriple> sb = triangle_set(b);
    if (sa == sb) return ::testing::AssertionSuccess();
    const auto show = [](const CornerTriple& t) {
        std::string text;
        char buffer[96];
        for (const Corner& c : t) {
            std::snprintf(buffer, sizeof buffer, "(%.17g, %.17g, %.17g) ", c[0], c[1], c[2]);
            text += buffer;
        }
        return text;
    };
    std::size_t i = 0;
    while (i < sa.size() && i < sb.size() && sa[i] == sb[i]) ++i;
    return ::testing::AssertionFailure()
           << sa.size() << " vs " << sb.size() << " triangles; first difference at sorted #" << i
           << ": " << (i < sa.size() ? show(sa[i]) : "none") << " vs "
           << (i < sb.size() ? show(sb[i]) : "none");
}

/// Writes a glTF 2 file by hand: one mesh named "road" (one primitive, the given primitive
/// mode, 4 = triangles) with float32 positions and uint32 indices in a .bin beside the
/// .gltf, and the given node list (JSON array elements) and scene roots. Lets the tests
/// build what the exporter never writes: node hierarchies, NaN in the binary buffer.
inline void write_gltf(const fs::path& path, const std::vector<float>& positions,
                       const std::vector<std::uint32_t>& indices, const std::string& nodes,
                       const std::string& scene_roots, int mode = 4) {
    const fs::path bin = fs::path(path).replace_extension(".bin");
    std::string bytes(reinterpret_cast<const char*>(positions.data()),
                      positions.size() * sizeof(float));
    const std::size_t position_bytes = bytes.size();
    bytes.append(reinterpret_cast<const char*>(indices.data()),
                 indices.size() * sizeof(std::uint32_t));
    write_file(bin, bytes);

    const std::string json =
        R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[)" + scene_roots +
        R"(]}],"nodes":[)" + nodes +
        R"(],"meshes":[{"name":"road","primitives":[{"attributes":{"POSITION":0},)" +
        R"("indices":1,"mode":)" + std::to_string(mode) + R"(}]}],"buffers":[{"uri":")" +
        bin.filename().string() + R"(","byteLength":)" + std::to_string(bytes.size()) +
        R"(}],"bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":)" +
        std::to_string(position_bytes) + R"(},{"buffer":0,"byteOffset":)" +
        std::to_string(position_bytes) + R"(,"byteLength":)" +
        std::to_string(bytes.size() - position_bytes) +
        R"(}],"accessors":[{"bufferView":0,"componentType":5126,"count":)" +
        std::to_string(positions.size() / 3) +
        R"(,"type":"VEC3"},{"bufferView":1,"componentType":5125,"count":)" +
        std::to_string(indices.size()) + R"(,"type":"SCALAR"}]})";
    write_file(path, json);
}

}  // namespace trackphys::test
