// Snapshot files: bit-exact round trips, and every truncation, every bit flip, another
// version, trailing bytes and invalid contents rejected with an error; an atomic write that
// leaves no file behind when it fails.
#include "trackphys/io/snapshot_file.hpp"

#include <bit>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>

#include <gtest/gtest.h>

#include "core/fnv1a.hpp"
#include "support/error_message.hpp"
#include "trackphys/error.hpp"
#include "trackphys/world/world.hpp"
#include "world/world_scenes.hpp"

namespace trackphys {
namespace {

using test::error_of;

namespace fs = std::filesystem;

// A small snapshot: one default car after a second on flat ground (~500 bytes).
WorldSnapshot small_snapshot() {
    World world(test::static_world_of(test::flat_grid(40.0, 8)));
    RigidBodyState start;
    start.position = {0.0, 0.52, 0.0};
    start.linear_velocity = {0.0, 0.0, 3.0};
    world.add_car(CarSpec::default_car(), start);
    world.car(0).set_inputs({0.4, 0.0, 0.2});
    for (int i = 0; i < 100; ++i) world.update();
    return world.save_state();
}

// Rewrites a header field and the checksum, as a tool writing another version would.
std::string with_u32_at(std::string bytes, std::size_t offset, std::uint32_t value) {
    for (int i = 0; i < 4; ++i)
        bytes[offset + static_cast<std::size_t>(i)] = static_cast<char>(value >> (8 * i));
    return bytes;
}

fs::path fresh_folder(const char* name) {
    const fs::path folder =
        fs::temp_directory_path() / ("trackphys_snapshot_test_" + std::string(name));
    fs::remove_all(folder);
    fs::create_directories(folder);
    return folder;
}

const std::string kUserData("drive \0 session", 15);

TEST(SnapshotFile, RoundTripIsBitExact) {
    const WorldSnapshot snapshot = small_snapshot();
    const std::string bytes = encode_snapshot(snapshot, kUserData);
    const SnapshotFile decoded = decode_snapshot(bytes);
    EXPECT_EQ(decoded.user_data, kUserData);
    EXPECT_EQ(decoded.world.update_count, 100u);
    ASSERT_EQ(decoded.world.cars.size(), 1u);
    EXPECT_EQ(std::bit_cast<std::uint64_t>(decoded.world.cars[0].state.position.y),
              std::bit_cast<std::uint64_t>(snapshot.cars[0].state.position.y));
    EXPECT_EQ(encode_snapshot(decoded.world, decoded.user_data), bytes) << "every bit comes back";

    const fs::path folder = fresh_folder("round_trip");
    save_snapshot(folder / "a.snap", snapshot, kUserData);
    EXPECT_EQ(encode_snapshot(load_snapshot(folder / "a.snap").world, kUserData), bytes);
    EXPECT_FALSE(fs::exists(folder / "a.snap.partial"));
    fs::remove_all(folder);
}

// The car pairs touching at the end of the last update come back bit for bit, and a list
// that is not pairs of the snapshot's cars in order is refused naming the pair.
TEST(SnapshotFile, TouchingCarPairsRoundTripAndAreChecked) {
    WorldSnapshot snapshot = small_snapshot();
    snapshot.cars.push_back(snapshot.cars[0]);
    snapshot.cars.push_back(snapshot.cars[0]);
    snapshot.touching = {{0, 1, 0.0125}, {1, 2, 0.0}};
    const std::string bytes = encode_snapshot(snapshot, kUserData);
    const SnapshotFile decoded = decode_snapshot(bytes);
    EXPECT_EQ(decoded.world.touching, snapshot.touching);
    EXPECT_EQ(encode_snapshot(decoded.world, kUserData), bytes);

    snapshot.touching = {{1, 2, 0.0}, {0, 1, 0.0125}};
    EXPECT_NE(error_of([&] {
                  decode_snapshot(encode_snapshot(snapshot));
              }).find("invalid contents: touching pair 1 (cars 0, 1): not after"),
              std::string::npos);
}

TEST(SnapshotFile, EveryTruncationIsRejected) {
    const std::string bytes = encode_snapshot(small_snapshot(), kUserData);
    ASSERT_GT(bytes.size(), 400u);
    for (std::size_t n = 0; n < bytes.size(); ++n)
        EXPECT_THROW(decode_snapshot(std::string_view(bytes).substr(0, n)), Error)
            << "first " << n << " bytes";
    EXPECT_NE(error_of([&] {
                  decode_snapshot(std::string_view(bytes).substr(0, bytes.size() - 1));
              }).find("truncated"),
              std::string::npos);
}

TEST(SnapshotFile, EveryBitFlipIsRejected) {
    const std::string bytes = encode_snapshot(small_snapshot(), kUserData);
    for (std::size_t i = 0; i < bytes.size(); ++i)
        for (int bit = 0; bit < 8; ++bit) {
            std::string flipped = bytes;
            flipped[i] = static_cast<char>(flipped[i] ^ (1 << bit));
            EXPECT_THROW(decode_snapshot(flipped), Error) << "byte " << i << " bit " << bit;
        }
    std::string corrupted = bytes;
    corrupted[200] = static_cast<char>(corrupted[200] ^ 0x10);
    EXPECT_NE(error_of([&] { decode_snapshot(corrupted); }).find("checksum mismatch"),
              std::string::npos);
}

TEST(SnapshotFile, OtherVersionsMagicAndTrailingBytesAreRejected) {
    const std::string bytes = encode_snapshot(small_snapshot());
    // Version 3 had no empty-list bits of the cars.
    EXPECT_NE(error_of([&] {
                  decode_snapshot(with_u32_at(bytes, 8, 3));
              }).find("format version 3, this build reads only version 4"),
              std::string::npos);
    EXPECT_NE(error_of([&] { decode_snapshot(with_u32_at(bytes, 8, 5)); }).find("format version 5"),
              std::string::npos);
    EXPECT_NE(error_of([&] { decode_snapshot(with_u32_at(bytes, 12, 1)); }).find("reserved"),
              std::string::npos);
    EXPECT_NE(error_of([&] {
                  decode_snapshot("v -50 0 -50\nv 50 0 -50\nv 50 0 50\nf 1 2 3\n");
              }).find("wrong magic"),
              std::string::npos);
    EXPECT_NE(error_of([&] { decode_snapshot(bytes + "x"); }).find("1 bytes of trailing garbage"),
              std::string::npos);
    EXPECT_NE(error_of([&] { decode_snapshot(""); }).find("shorter than the 32-byte header"),
              std::string::npos);
}

// A payload that checks out but holds what no world could: rejected at load, whoever wrote it.
TEST(SnapshotFile, InvalidContentsAreRejected) {
    WorldSnapshot nan_velocity = small_snapshot();
    nan_velocity.cars[0].state.linear_velocity.z = std::numeric_limits<double>::quiet_NaN();
    EXPECT_NE(error_of([&] {
                  decode_snapshot(encode_snapshot(nan_velocity));
              }).find("invalid contents: car 0: linear_velocity is not finite"),
              std::string::npos);
    WorldSnapshot bad_mode = small_snapshot();
    bad_mode.settings.mid_phase = static_cast<MidPhaseMode>(7);
    EXPECT_NE(
        error_of([&] { decode_snapshot(encode_snapshot(bad_mode)); }).find("not a mid-phase mode"),
        std::string::npos);
}

// A count that claims more records than the bytes left fails before allocating them.
TEST(SnapshotFile, HugeCountsAreRejectedWithoutAllocating) {
    WorldSnapshot snapshot = small_snapshot();
    snapshot.colliders.clear();
    std::string bytes = encode_snapshot(snapshot);
    // The collider count is the payload's first field; re-seal the checksum.
    bytes = with_u32_at(bytes, 32, 0xffffffffu);
    core::Fnv1a hash;
    hash.add(bytes.data() + 32, bytes.size() - 32);
    for (int i = 0; i < 8; ++i)
        bytes[24 + static_cast<std::size_t>(i)] = static_cast<char>(hash.value >> (8 * i));
    EXPECT_NE(error_of([&] { decode_snapshot(bytes); }).find("collider count 4294967295"),
              std::string::npos);
}

TEST(SnapshotFile, AFailedWriteLeavesNoFile) {
    const fs::path folder = fresh_folder("failed_write");
    const WorldSnapshot snapshot = small_snapshot();

    // The output folder does not exist.
    const fs::path missing = folder / "no" / "such" / "folder" / "a.snap";
    EXPECT_NE(error_of([&] { save_snapshot(missing, snapshot); }).find("cannot write the snapshot"),
              std::string::npos);
    EXPECT_FALSE(fs::exists(folder / "no"));

    // The destination is a folder: the rename fails, the temporary file is removed.
    fs::create_directories(folder / "taken" / "inside");
    EXPECT_NE(error_of([&] {
                  save_snapshot(folder / "taken", snapshot);
              }).find("cannot move the snapshot"),
              std::string::npos);
    EXPECT_FALSE(fs::exists(folder / "taken.partial"));

    // Loading what is not there.
    EXPECT_NE(error_of([&] {
                  load_snapshot(folder / "absent.snap");
              }).find("snapshot '" + (folder / "absent.snap").string() + "': no such file"),
              std::string::npos);
    // Overwriting a snapshot replaces it whole.
    save_snapshot(folder / "a.snap", snapshot);
    WorldSnapshot later = snapshot;
    later.update_count += 1;
    save_snapshot(folder / "a.snap", later);
    EXPECT_EQ(load_snapshot(folder / "a.snap").world.update_count, snapshot.update_count + 1);
    std::size_t files = 0;
    for ([[maybe_unused]] const auto& entry : fs::directory_iterator(folder)) ++files;
    EXPECT_EQ(files, 2u) << "a.snap and the taken/ folder, nothing else";
    fs::remove_all(folder);
}

// load_snapshot reads the header, then only the payload it announces, and only when the file
// holds exactly that: a file cut short or grown is refused, naming it, before its payload is
// read.
TEST(SnapshotFile, LoadRefusesAFileWhoseSizeIsNotTheHeaders) {
    const fs::path folder = fresh_folder("file_size");
    const std::string bytes = encode_snapshot(small_snapshot());
    const auto write = [&](const char* name, const std::string& text) {
        std::ofstream(folder / name, std::ios::binary) << text;
        return folder / name;
    };
    const fs::path grown = write("grown.snap", bytes + "xyz");
    EXPECT_NE(error_of([&] {
                  load_snapshot(grown);
              }).find("snapshot '" + grown.string() + "': 3 bytes of trailing garbage"),
              std::string::npos);
    const fs::path cut = write("cut.snap", bytes.substr(0, 100));
    EXPECT_NE(error_of([&] { load_snapshot(cut); })
                  .find("snapshot '" + cut.string() + "': truncated: the header announces " +
                        std::to_string(bytes.size() - 32) + " payload bytes, the file has 68"),
              std::string::npos);
    const fs::path folder_path = folder / "a_folder.snap";
    fs::create_directories(folder_path);
    EXPECT_NE(error_of([&] { load_snapshot(folder_path); }).find("': is a folder, not a file"),
              std::string::npos);
    EXPECT_EQ(load_snapshot(write("whole.snap", bytes)).world.update_count,
              small_snapshot().update_count);
    fs::remove_all(folder);
}

// fuzz_snapshot's two-car seed is its one-car seed (a snapshot of `trackphys drive`) with the
// car copied 1.5 m to its side and the two listed as touching, so that mutated inputs reach a
// touching list that restores. Built here from the one-car seed, it must be the committed file:
// after a format change this test writes the new seed for fuzz/seeds to take.
TEST(SnapshotFile, TheTouchingFuzzSeedIsTheDriveSeedWithItsCarTwice) {
    const fs::path seeds(TRACKPHYS_SNAPSHOT_SEEDS_DIR);
    SnapshotFile file = load_snapshot(seeds / "flat_ground.snap.seed");
    ASSERT_EQ(file.world.cars.size(), 1u) << "drive saves one car";
    ASSERT_TRUE(file.world.touching.empty());
    CarSnapshot beside = file.world.cars[0];
    beside.state.position.x += 1.5;
    file.world.cars.push_back(beside);
    file.world.touching = {{0, 1, 0.01}};
    const std::string expected = encode_snapshot(file.world, file.user_data);

    std::ifstream committed(seeds / "two_touching.snap.seed", std::ios::binary);
    const std::string actual{std::istreambuf_iterator<char>(committed), {}};
    if (actual != expected) {
        const fs::path made = fs::absolute("two_touching.snap.seed");
        std::ofstream(made, std::ios::binary) << expected;
        FAIL() << "fuzz/seeds/fuzz_snapshot/two_touching.snap.seed is not the one-car seed with "
                  "its car twice: take "
               << made << " in its place";
    }
    EXPECT_EQ(decode_snapshot(actual).world.touching.size(), 1u);
}

}  // namespace
}  // namespace trackphys
