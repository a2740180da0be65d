#pragma once

// The real-world track meshes of the tests: four TORCS tracks that
// scripts/fetch_torcs_track.sh puts into the build folder (CTest's fixture torcs_tracks runs
// it first; scripts/test.sh too). A test on one skips, saying why, where they could not be
// had (a machine without network).

#include <filesystem>
#include <map>
#include <string>

#include <gtest/gtest.h>

#include "trackphys/geometry/triangle_mesh.hpp"
#include "trackphys/io/mesh_io.hpp"

namespace trackphys::test {

/// The tracks' names (DIR/<name>.ac).
inline const std::string kRealTracks[] = {"g-track-1", "c-speedway", "e-track-4", "alpine-1"};

/// A parameterized test's name for a track (GoogleTest allows no '-').
inline std::string real_track_test_name(const ::testing::TestParamInfo<std::string>& info) {
    std::string name = info.param;
    for (char& c : name)
        if (c == '-') c = '_';
    return name;
}

/// The track's mesh, loaded once per test program, or nullptr with the reason in *why.
inline const TriangleMesh* real_track(const std::string& name, std::string* why) {
    static std::map<std::string, TriangleMesh> loaded;
    if (auto it = loaded.find(name); it != loaded.end()) return &it->second;
    const std::filesystem::path path = std::filesystem::path(TRACKPHYS_TORCS_DIR) / (name + ".ac");
    if (!std::filesystem::exists(path)) {
        *why = path.string() +
               " is missing: scripts/fetch_torcs_track.sh " TRACKPHYS_TORCS_DIR
               " fetches it (from an installed torcs-data, else with apt-get download, which "
               "needs network)";
        return nullptr;
    }
    return &loaded.emplace(name, load_mesh(path)).first->second;
}

}  // namespace trackphys::test

/// Declares `const TriangleMesh& mesh` for the track `name`, or skips the test saying why.
#define TRACKPHYS_REAL_TRACK_OR_SKIP(mesh, name)                                               \
    std::string mesh##_missing;                                                                \
    const TriangleMesh* mesh##_pointer = ::trackphys::test::real_track(name, &mesh##_missing); \
    if (mesh##_pointer == nullptr) GTEST_SKIP() << mesh##_missing;                             \
    const TriangleMesh& mesh = *mesh##_pointer
