#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

#include "trackphys/export.hpp"
#include "trackphys/world/world_snapshot.hpp"

namespace trackphys {

/// What a snapshot file holds: a world snapshot, and bytes of the application's own (the
/// `trackphys drive` command keeps its autopilot's progress and its figures there), stored
/// and checksummed with it but not interpreted.
struct SnapshotFile {
    WorldSnapshot world;
    std::string user_data;
};

/// The snapshot format this build writes and the only one it reads.
inline constexpr std::uint32_t kSnapshotFormatVersion = 4;

/// The bytes of a snapshot file. Layout, every number little-endian, doubles as their IEEE
/// bits (so they come back bit-exact):
///
///     header (32 bytes): magic "TPSNAP\x1a\n" (8), format version u32, reserved u32 = 0,
///                        payload length u64, FNV-1a 64 checksum of the payload u64
///     payload:  u32 colliders, each {u64 mesh triangles, u64 kept, u64 content hash}
///               settings {f64 dt_update, i32 steps, i32 substeps, f64 gravity[3],
///                         f64 broad_phase_margin, u32 mid_phase, u32 mid_phase_look_ahead,
///                         f64 mid_phase_slack, f64 max_car_speed,
///                         f64 max_car_angular_speed, f64 max_spawn_distance}
///               u64 update count
///               u32 cars, each {u64 spec fingerprint, f64 position[3], orientation[4] (w x y z),
///                               linear_velocity[3], angular_velocity[3], f64 throttle, brake,
///                               steer, u32 ellipsoids, each {f64 suspension, f64 depth,
///                               f64 normal[3], f64 point[3], u32 collider, u32 triangle},
///                               u64 empty lists, u64 resets, u32 vehicle wheels + 1 (0: no vehicle
///                               model), each {f64 spin, slip_ratio, lateral_slip,
///                               road_torque},
///                               and with a vehicle u32 gear, f64 shift_time_left, clutch}
///               u32 touching pairs, each {u32 car_a, u32 car_b, f64 deepest}
///               u64 user data length, the user data
TRACKPHYS_API std::string encode_snapshot(const WorldSnapshot& snapshot,
                                          std::string_view user_data = {});

/// Reads encode_snapshot's bytes back. Throws trackphys::Error, naming the problem, for a
/// wrong magic, another format version, a checksum that does not match, a payload that is
/// truncated, too long for its contents or followed by trailing bytes, and for a snapshot
/// that fails WorldSnapshot::validate(): nothing is ever half-loaded.
TRACKPHYS_API SnapshotFile decode_snapshot(std::string_view bytes);

/// Writes the snapshot file atomically: to a temporary file beside `path`, then renamed
/// over it, so a failed write (no such folder, full disk) leaves no file and never a
/// partial one. Throws trackphys::Error naming the path and the reason.
TRACKPHYS_API void save_snapshot(const std::filesystem::path& path, const WorldSnapshot& snapshot,
                                 std::string_view user_data = {});

/// Reads and decodes a snapshot file (decode_snapshot); throws trackphys::Error
/// "snapshot '<path>': <reason>", also for a path that is not a regular file (a folder, a
/// device, a pipe) and for a file whose size is not the header's plus the payload length
/// it announces: that is checked before the payload is read.
TRACKPHYS_API SnapshotFile load_snapshot(const std::filesystem::path& path);

}  // namespace trackphys
