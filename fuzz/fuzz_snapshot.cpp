// libFuzzer target: snapshot loading, bytes -> decode_snapshot -> World::restore_state ->
// a few updates.
//
// The world is the one `trackphys drive --mesh tests/data/flat_ground.obj --spawn 0,3,0`
// drives on, with as many default cars as the snapshot has (up to 4), so that the seeds (a
// snapshot that drive saved, and the same with its car twice, the two touching) restore.
// Each input is tried twice: as it is, which exercises the header checks (magic, version,
// length, checksum), and re-sealed (its payload length and checksum rewritten to match), which lets mutations reach
// the payload parser, the snapshot's validation and restore_state's checks.
//
// Every input must be rejected with trackphys::Error, or restore. A restored world must save
// exactly the bytes it was restored from (nothing lost, nothing half-loaded) and then update
// with finite states (the reset policy catches the rest); any other exception, crash,
// sanitizer report or hang is a finding.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <string_view>

#include "core/fnv1a.hpp"
#include "trackphys/collision/static_collider.hpp"
#include "trackphys/collision/static_world.hpp"
#include "trackphys/error.hpp"
#include "trackphys/geometry/mesh_chunks.hpp"
#include "trackphys/io/mesh_io.hpp"
#include "trackphys/io/snapshot_file.hpp"
#include "trackphys/math/types.hpp"
#include "trackphys/world/world.hpp"

namespace {

using trackphys::Error;

constexpr std::size_t kHeaderBytes = 32;
constexpr int kUpdates = 5;
constexpr std::size_t kMaxCars = 4;

// Loaded once per process, in the 100 m cells drive --mesh splits a mesh into (a collider
// each), so that drive's snapshots are of this world.
const std::shared_ptr<const trackphys::StaticWorld>& statics() {
    static const std::shared_ptr<const trackphys::StaticWorld> built = [] {
        auto world = std::make_shared<trackphys::StaticWorld>();
        for (const trackphys::TriangleMesh& chunk :
             trackphys::split_into_chunks(trackphys::load_mesh(TRACKPHYS_FUZZ_GROUND), 100.0))
            world->add(std::make_shared<trackphys::StaticCollider>(chunk));
        return world;
    }();
    return built;
}

[[noreturn]] void finding(const char* what, const std::string& detail = {}) {
    std::fprintf(stderr, "fuzz_snapshot: %s %s\n", what, detail.c_str());
    std::abort();
}

// The same bytes with the header's payload length and checksum made to match the payload.
std::string resealed(std::string bytes) {
    const std::uint64_t length = bytes.size() - kHeaderBytes;
    trackphys::core::Fnv1a checksum;
    checksum.add(bytes.data() + kHeaderBytes, length);
    for (std::size_t i = 0; i < 8; ++i) {
        bytes[16 + i] = static_cast<char>(length >> (8 * i));
        bytes[24 + i] = static_cast<char>(checksum.value >> (8 * i));
    }
    return bytes;
}

void try_snapshot(std::string_view bytes) {
    trackphys::SnapshotFile file;
    try {
        file = trackphys::decode_snapshot(bytes);
    } catch (const Error&) {
        return;
    }
    // As many default cars as the snapshot has (a few at most), side by side, so that a
    // touching list between them restores too.
    trackphys::World world(statics());
    const std::size_t cars = std::clamp<std::size_t>(file.world.cars.size(), 1, kMaxCars);
    for (std::size_t i = 0; i < cars; ++i) {
        trackphys::RigidBodyState start;
        start.position = {4.0 * static_cast<double>(i),
                          trackphys::CarSpec::default_car().lowest_point_depth() + 0.001, 0.0};
        world.add_car(trackphys::CarSpec::default_car(), start);
    }
    try {
        world.restore_state(file.world);
    } catch (const Error&) {
        return;
    }
    if (trackphys::encode_snapshot(world.save_state(), file.user_data) != bytes)
        finding("the restored world does not save the bytes it was restored from");
    for (int u = 0; u < kUpdates; ++u) {
        try {
            world.update();
        } catch (const Error& e) {
            finding("update of a restored world threw:", e.what());
        }
        for (std::size_t i = 0; i < cars; ++i) {
            const trackphys::RigidBodyState& s = world.car(i).state();
            if (!(trackphys::is_finite(s.position) && trackphys::is_finite(s.orientation) &&
                  trackphys::is_finite(s.linear_velocity) &&
                  trackphys::is_finite(s.angular_velocity)))
                finding("non-finite car state after an update");
        }
    }
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    statics();
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view bytes(reinterpret_cast<const char*>(data), size);
    try_snapshot(bytes);
    if (size >= kHeaderBytes) try_snapshot(resealed(std::string(bytes)));
    return 0;
}
