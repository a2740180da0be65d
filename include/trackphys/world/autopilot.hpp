#pragma once

#include <cstddef>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "trackphys/dynamics/car.hpp"
#include "trackphys/export.hpp"
#include "trackphys/track/track.hpp"

namespace trackphys {

/// How the autopilot drives.
struct AutopilotSettings {
    double target_speed = 600.0 / 3.6;  ///< m/s on straights
    /// Share of the tyres' friction the speed profile plans to use in turns (the rest is
    /// margin for steering corrections and bumps).
    double grip_use = 0.75;
    /// Deceleration the profile plans for braking into turns (m/s^2, before downforce).
    double braking = 6.0;
    /// A car with a vehicle model plans braking at this share of its tyres' longitudinal
    /// peak instead: about what `braking` is of the arcade car's grip, so that braking
    /// into a turn leaves the tyres lateral grip to turn with.
    double braking_grip_use = 0.5;
    double lookahead_min = 10.0;   ///< m ahead of the car at low speed
    double lookahead_time = 0.45;  ///< s of travel added to the look-ahead distance
    /// Gain of the yaw-rate feedback in the steering (0 = pure pursuit only).
    double yaw_damping = 0.5;

    /// Empty when every field is finite, target_speed, grip_use, braking and
    /// braking_grip_use > 0 and the rest >= 0; else the first field that is not, named
    /// ("AutopilotSettings.grip_use must be finite and > 0, got nan").
    TRACKPHYS_API std::string validate() const;
};

/// Where an Autopilot is along its track: all it remembers between calls (besides what
/// its constructor computes from the track, the car and the settings), so that a saved
/// drive continues identically (World::save_state for the cars, this for the driver).
struct AutopilotProgress {
    std::size_t nearest_sample = 0;  ///< Autopilot::nearest_sample()
    int laps = 0;                    ///< Autopilot::laps()
    bool located = false;            ///< false until the first drive() or locate()
};

/// A track's centreline held once for any number of autopilots: a race's field shares one
/// instead of each car keeping its own copy of every sample.
using SharedCenterline = std::shared_ptr<const std::vector<CenterlineSample>>;

/// Drives a car around a generated track unattended: a speed profile computed from the
/// centreline (the fastest each turn's radius, bank, grip and downforce allow, with
/// braking distance before it), throttle and brake to follow it, and pure-pursuit steering
/// towards a point on the centreline ahead. A moved-from Autopilot holds no centreline: assign
/// to it or destroy it, nothing else.
class TRACKPHYS_API Autopilot {
  public:
    /// Keeps its own copy of the track's centreline.
    Autopilot(const Track& track, const CarSpec& car, AutopilotSettings settings = {});
    /// Shares `centerline` (a closed loop of length_m metres, as Track's) with whoever else
    /// holds it; copies of an Autopilot share theirs too. Throws trackphys::Error for a null
    /// or shorter than three samples centreline, a length that is not finite and > 0, or
    /// settings that AutopilotSettings::validate refuses.
    Autopilot(SharedCenterline centerline, double length_m, const CarSpec& car,
              AutopilotSettings settings = {});

    /// Inputs for the car's current state; also advances the progress along the track.
    CarInputs drive(const Car& car);
    /// Advances the progress along the track (nearest sample, laps) to the car's current
    /// position, without computing inputs.
    void locate(const Car& car);

    /// The planned speed (m/s) at centreline sample i.
    double planned_speed(std::size_t i) const { return planned_speed_[i]; }
    /// The centreline sample nearest the car at the last drive() call.
    std::size_t nearest_sample() const { return nearest_; }
    /// Distance driven along the centreline since the start (m), laps included.
    double distance_along() const { return laps_ * length_ + centerline()[nearest_].distance; }
    /// Completed laps: times the car crossed the start line going forward.
    int laps() const { return laps_; }

    /// Steer for a line this far left of the centreline (m; negative: right), e.g. to pass
    /// a slower car. 0 until set; not part of the progress (a race sets it every update).
    void set_lane_offset(double metres) { lane_offset_ = metres; }
    double lane_offset() const { return lane_offset_; }
    /// Drive no faster than this (m/s), e.g. behind a slower car. Infinite until set; not
    /// part of the progress (a race sets it every update).
    void set_speed_limit(double metres_per_second) { speed_limit_ = metres_per_second; }
    double speed_limit() const { return speed_limit_; }
    /// Whether drive() or locate() has found the car yet (nearest_sample() is 0 until then).
    bool located() const { return located_; }

    const AutopilotSettings& settings() const { return settings_; }
    /// The centreline it drives along (shared with the autopilots given the same one).
    const std::vector<CenterlineSample>& centerline() const { return *centerline_; }

    /// The progress to save beside a world snapshot.
    AutopilotProgress progress() const { return {nearest_, laps_, located_}; }
    /// Continues from saved progress. Throws trackphys::Error when the sample is not on
    /// this track's centreline or laps is negative.
    void set_progress(const AutopilotProgress& progress);
    /// Throws what set_progress() would throw for `progress`, changing nothing.
    void check_progress(const AutopilotProgress& progress) const;

  private:
    std::size_t find_nearest(const glm::dvec3& position) const;
    std::size_t sample_ahead(std::size_t from, double distance) const;

    SharedCenterline centerline_;
    std::vector<double> planned_speed_;
    double length_;
    AutopilotSettings settings_;
    double wheelbase_;
    double max_steer_angle_;
    // The longest chord between neighbouring centreline samples (m), for find_nearest.
    double max_sample_gap_ = 0.0;
    std::size_t nearest_ = 0;
    int laps_ = 0;
    bool located_ = false;
    double lane_offset_ = 0.0;
    double speed_limit_ = std::numeric_limits<double>::infinity();
};

}  // namespace trackphys
