#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "trackphys/world/autopilot.hpp"

namespace trackphys::cli {

/// What `trackphys drive` keeps beside the world in a snapshot file (its user data, as
/// JSON): the options that decide how the drive continues, the autopilot's progress and
/// the report's running figures, so that `--resume` continues the drive exactly and
/// reports it whole.
struct DriveSession {
    bool free_mode = false;
    std::uint64_t seed = 0;         ///< generated track (not in free mode)
    double target_speed_kmh = 0.0;  ///< autopilot (not in free mode)
    double throttle = 0.0;          ///< free mode's fixed inputs
    double steer = 0.0;
    std::optional<AutopilotProgress> autopilot;
    double distance_m = 0.0;
    double top_speed_kmh = 0.0;
    std::vector<double> lap_times_s;
    std::vector<double> surface_grips;  ///< --surface-grips (Scenario::surfaces), by id
};

/// The session as JSON text (doubles round-trip exactly).
std::string session_json(const DriveSession& session);

/// Parses session_json's text; throws trackphys::Error when it is not a drive session.
DriveSession parse_session(std::string_view json);

/// Throws trackphys::Error naming the first option in which `now` (this run's options)
/// differs from `saved` (the snapshot's drive): a resumed drive must be the same drive.
void check_same_drive(const DriveSession& saved, const DriveSession& now);

}  // namespace trackphys::cli
