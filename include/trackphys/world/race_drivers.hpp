#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "trackphys/dynamics/car_spec.hpp"
#include "trackphys/export.hpp"
#include "trackphys/track/track.hpp"
#include "trackphys/world/autopilot.hpp"
#include "trackphys/world/race_grid.hpp"
#include "trackphys/world/world.hpp"

namespace trackphys {

/// The autopilot a race gives every car (its target speed is then set per car): a shorter
/// look-ahead than a lone lap's, so that a car keeps to its lane through the turns instead
/// of cutting them by metres (docs/design.md, "Races").
TRACKPHYS_API AutopilotSettings race_autopilot();

namespace detail {
// Where a car of a race is across the road (m left of the centreline) and along it (m from
// the start line), at its autopilot's nearest sample.
struct RoadPosition {
    double across;
    double along;
};
}  // namespace detail

/// How a field of autopilots races.
struct RaceSettings {
    /// Each car's pace: its target speed on straights (km/h) and the share of its tyres'
    /// grip it plans to use in turns (AutopilotSettings::grip_use). The pole car has the
    /// slowest, the last car of the grid the fastest, the others spread evenly between, so
    /// the field overtakes: on a track of turns the grip share sets the lap time, the
    /// target speed only the top speed on the longest straights.
    double slowest_kmh = 420.0;
    double fastest_kmh = 600.0;
    double least_grip_use = 0.65;
    double most_grip_use = 0.75;
    /// The two lanes are this far (m) left and right of the centreline: a car keeps to the
    /// lane of its grid column and moves to the other one to pass. Near enough the centre
    /// that a car in a lane, its line-keeping error and a bump from a car beside it stay
    /// clear of the wall.
    double lane_offset = 2.0;
    /// A lane is blocked by a slower car in it (within lane_width of its line: one that
    /// closes in on it, or of a slower pace) from a few metres behind (alongside) to
    /// pass_look_ahead ahead along the track (m).
    double pass_look_ahead = 60.0;
    double lane_width = 2.5;
    /// A car moves into a lane only when nobody is in it from 20 m behind (the mirror) to
    /// merge_gap ahead (m): it pulls out into a gap, not onto the bumper of a slower car.
    /// The lanes are read no farther than pass_look_ahead, so merge_gap must not exceed it
    /// (both as large as the track: nobody ever passes).
    double merge_gap = 15.0;
    /// A car pulls out to pass when the car ahead in its lane has the slower pace or it
    /// closes in on that car faster than this (m/s).
    double pass_closing = 1.0;
    /// No lane change begins where the turn already asks more than this (m/s^2 across the
    /// road, v^2 |curvature|) of the tyres: a swerve adds its own sideways push, and a car
    /// near the limit slides. Infinite: lanes change in any turn.
    double swerve_turn_accel = 6.0;
    /// Behind a car in its lane a car keeps follow_distance (m, centre to centre) plus
    /// follow_time (s) of its speed, matching the speed of the car ahead: pushed from
    /// behind in a turn, a car spins.
    double follow_distance = 6.0;
    double follow_time = 0.05;
    /// How fast (m/s across the road) a car's line moves to a new lane: a lane change is a
    /// smooth swerve, not a step the steering would overshoot.
    double lane_change_speed = 3.0;
    /// A car whose centre of mass ends an update farther than this (m) from the centreline
    /// has left the track (over a wall, off the map, falling): it is put back on the road
    /// where it left it (a rescue; see RaceDrivers::after_update).
    double rescue_distance = 30.0;
    /// Every car's autopilot; its target_speed and grip_use are replaced by the spread
    /// above.
    AutopilotSettings driver = race_autopilot();
    RaceGridSettings grid;
};

/// Where a race is: all RaceDrivers remembers between updates, to save beside a world
/// snapshot so that a resumed race continues identically.
struct RaceProgress {
    std::vector<AutopilotProgress> pilots;  ///< per car
    std::vector<double> lanes;  ///< the lane each car heads for (m left of the centreline)
    std::vector<double> lines;  ///< the line each car steers for now, on its way there (m)
    std::vector<std::vector<double>> lap_times;  ///< per car (s)
    std::vector<double> last_crossings;          ///< per car: its last start-line crossing (s)
    std::vector<std::uint64_t> rescues;          ///< per car: times it was put back on the road
};

/// A field of cars racing laps of a generated track: a starting grid (race_grid), one
/// Autopilot per car with its own pace, and a lane per car, chosen every update from the
/// field: a car leaves its own lane when a slower car is ahead in it and the other lane is
/// free (nobody in it from 20 m behind, as a driver checks the mirror, to merge_gap ahead,
/// and the car ahead there not slower), and comes back once its own lane is free and
/// nothing in it holds the car up; no lane change begins in a turn that already asks more
/// than swerve_turn_accel of sideways grip at the car's speed; else it
/// stays, and follows the car ahead at a distance (follow_distance, follow_time), which it
/// may still bump under braking. Its line moves to a new lane at lane_change_speed, and a
/// lane change once begun is finished before the next. Everything it decides is a
/// function of the cars' states and its progress, so a race is as deterministic as its
/// World.
///
/// Laps: the grid stands behind the start line, so a car's first crossing starts its lap
/// 1 (a flying start); laps(i) counts the crossings after it.
class TRACKPHYS_API RaceDrivers {
  public:
    /// Throws trackphys::Error for no cars, speeds or grip shares that are not finite and
    /// > 0 or in the wrong order, negative lane distances or rule thresholds, a
    /// merge_gap beyond pass_look_ahead, or a track whose length is not finite and > 20 m or
    /// with a centreline sample outside [0, length_m) along it. The drivers keep their own
    /// copy of the track's centreline: `track` need not outlive them.
    RaceDrivers(const Track& track, const CarSpec& car, std::size_t cars,
                RaceSettings settings = {});

    /// Adds the field to `world` (which must hold no cars yet) on the grid.
    void add_cars(World& world) const;
    /// Sets every car's inputs for the next World::update, from where every car stands
    /// (the first call locates them all before any car decides). Throws trackphys::Error,
    /// as after_update does, when the world's car count is not the race's.
    void drive(World& world);
    /// Call after each World::update: counts the laps each car completed in it, timed at
    /// world.time(), and rescues every car that left the track (RaceSettings::
    /// rescue_distance): it is put back in its own lane at its nearest centreline sample, or
    /// the first sample after it with no other car within a car's length or two, facing
    /// along the track at the speed its autopilot plans there, its inputs kept.
    void after_update(World& world);

    std::size_t car_count() const { return pilots_.size(); }
    // Each accessor of one car throws trackphys::Error naming the car and car_count() past
    // the last car, as World and PhysicsRunner do.
    /// Laps car `car` has completed: its crossings of the start line after the first.
    int laps(std::size_t car) const;
    /// Fewest laps completed by any car.
    int fewest_laps() const;
    /// Car i's lap times (s), one per completed lap.
    const std::vector<double>& lap_times(std::size_t car) const {
        return progress_.lap_times[checked(car, "RaceDrivers::lap_times")];
    }
    /// Car i's target speed on straights (m/s).
    double target_speed(std::size_t car) const {
        return autopilot(car, "RaceDrivers::target_speed").settings().target_speed;
    }
    /// Car i's share of its tyres' grip planned in turns (AutopilotSettings::grip_use).
    double grip_use(std::size_t car) const {
        return autopilot(car, "RaceDrivers::grip_use").settings().grip_use;
    }
    /// Times car i left the track and was put back on it.
    std::uint64_t rescues(std::size_t car) const {
        return progress_.rescues[checked(car, "RaceDrivers::rescues")];
    }
    const Autopilot& autopilot(std::size_t car) const {
        return autopilot(car, "RaceDrivers::autopilot");
    }

    /// The race's progress, to save beside a world snapshot, and back. set_progress
    /// throws trackphys::Error for a progress of another field size or as
    /// Autopilot::set_progress does for any car's, changing nothing.
    RaceProgress progress() const;
    void set_progress(const RaceProgress& progress);

  private:
    using RoadPosition = detail::RoadPosition;
    // car, or trackphys::Error naming the caller, car and car_count() past the last car.
    std::size_t checked(std::size_t car, const char* caller) const;
    const Autopilot& autopilot(std::size_t car, const char* caller) const {
        return pilots_[checked(car, caller)];
    }
    // Throws unless the world holds as many cars as the race drives.
    void check_field(const World& world, const char* caller) const;
    RoadPosition road_position(const World& world, std::size_t car) const;
    // The lane of car i's grid column (m left of the centreline).
    double own_lane(std::size_t car) const;
    // Car i's lane for the next update (m left of the centreline).
    double lane(const World& world, std::size_t i) const;
    // Car i's line for the next update: from its current one towards its lane.
    double line_towards(std::size_t i, double lane, double dt) const;
    // The nearest car ahead of car i within lane_width of `line`, from `from` m (negative:
    // behind, alongside) to pass_look_ahead m along the track: which, how far ahead (m,
    // infinite for none) and how fast car i closes in on it (m/s). Reads road_positions_
    // and cars_along_.
    struct CarAhead {
        std::size_t car;
        double gap;
        double closing;
    };
    CarAhead car_ahead(const World& world, std::size_t i, double line, double from) const;
    // Whether `ahead` holds car i up: car i closes in on it faster than `closing` (m/s),
    // or it has the slower pace.
    bool slower(std::size_t i, const CarAhead& ahead, double closing) const;
    // The fastest car i may drive (m/s) at `speed` with `ahead` in its lane: the speed of
    // the car ahead, more or less as the gap is above or below the following distance.
    double following_speed(const CarAhead& ahead, double speed) const;
    // Whether car i is farther than rescue_distance from its nearest centreline sample.
    bool left_track(const World& world, std::size_t i) const;
    // Puts car i back on the road (after_update).
    void rescue(World& world, std::size_t i);

    std::shared_ptr<const Track> route_;  // the track's centreline and length (route_of)
    CarSpec car_;
    RaceSettings settings_;
    std::vector<Autopilot> pilots_;
    RaceProgress progress_;                     // all but the autopilots' (pilots stays empty)
    std::vector<double> next_lanes_;            // this update's, chosen before any is set
    std::vector<RoadPosition> road_positions_;  // every car's, during drive()
    std::vector<std::uint32_t> cars_along_;     // road_positions_' cars in track order
};

}  // namespace trackphys
