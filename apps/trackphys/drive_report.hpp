#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <glm/vec3.hpp>
#include <nlohmann/json.hpp>

#include "trackphys/profile/profile_statistics.hpp"

namespace trackphys::cli {

/// The write-up's budget for one update (us), printed beside ours by drive and bench.
inline constexpr double kWriteupTypicalUs = 4000.0;
inline constexpr double kWriteupSpikeUs = 8000.0;

/// Everything `trackphys drive` reports about a run.
struct DriveReport {
    std::string scene;
    std::size_t triangles = 0;
    std::uint64_t updates = 0;
    double simulated_s = 0.0;
    double wall_s = 0.0;
    int laps_completed = 0;
    std::vector<double> lap_times_s;
    double top_speed_kmh = 0.0;
    double distance_m = 0.0;
    glm::dvec3 final_position{0.0};
    std::uint64_t state_hash = 0;
    std::uint64_t resets = 0;  ///< World::car_resets (the reset policy)
    std::string last_reset;    ///< its last reason, or empty
    ProfileStatistics profile;
};

/// The human-readable table (stdout).
void print_drive_report(const DriveReport& report);

/// The same figures as JSON (keys pinned by issue 6), written atomically to path.
void write_drive_json(const DriveReport& report, const std::filesystem::path& path);

/// The per-update and per-phase times table, with the write-up's budget (stdout).
void print_profile_table(const ProfileStatistics& profile);

/// The profile's "update_us" and "phases_us" (each a summary_json) into a JSON report.
void add_profile_json(nlohmann::json& json, const ProfileStatistics& profile);

/// {"mean", "p50", "p99", "max"} of a summary, as the JSON reports write it.
nlohmann::json summary_json(const Summary& summary);

/// Hex form of a state hash, as printed and stored.
std::string hash_hex(std::uint64_t hash);

}  // namespace trackphys::cli
