#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "trackphys/profile/profile_statistics.hpp"

namespace trackphys::cli {

/// One car's race.
struct RaceCarResult {
    std::size_t car = 0;      ///< index on the grid (0 = pole)
    double target_kmh = 0.0;  ///< its autopilot's speed on straights
    double grip_use = 0.0;    ///< its autopilot's share of the grip in turns: its pace
    int laps = 0;             ///< completed
    double distance_m = 0.0;  ///< along the centreline since the grid, for the order
    std::vector<double> lap_times_s;
    std::uint64_t resets = 0;   ///< the World's and the rescues
    std::uint64_t rescues = 0;  ///< times it left the track and was put back on it
};

/// Everything `trackphys race` reports.
struct RaceReport {
    std::string scene;
    std::size_t cars = 0;
    int threads = 0;
    std::uint64_t updates = 0;
    double simulated_s = 0.0;
    double wall_s = 0.0;
    int laps_completed = 0;                     ///< the fewest over the cars
    std::vector<RaceCarResult> classification;  ///< by laps, then distance, leader first
    std::uint64_t car_contacts = 0;             ///< UpdateProfile::car_contacts, summed
    double max_car_penetration_m = 0.0;
    std::uint64_t car_touches = 0;  ///< car pairs that began touching (World::contact_events)
    std::uint64_t body_hits = 0;    ///< body ellipsoids that hit the static world
    std::uint64_t resets = 0;       ///< over all cars, rescues included
    std::uint64_t rescues = 0;      ///< over all cars
    std::uint64_t state_hash = 0;
    ProfileStatistics profile;
};

/// The classification and the per-update profile of the whole world (stdout).
void print_race_report(const RaceReport& report);

/// The figures as JSON (keys pinned by issue 16), written atomically to path.
void write_race_json(const RaceReport& report, const std::filesystem::path& path);

}  // namespace trackphys::cli
