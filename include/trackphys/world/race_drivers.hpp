#pragma once

#include <cstddef>
#include <span>
#include <vector>

#include "trackphys/dynamics/car_spec.hpp"
#include "trackphys/export.hpp"
#include "trackphys/track/track.hpp"
#include "trackphys/world/autopilot.hpp"
#include "trackphys/world/race_grid.hpp"
#include "trackphys/world/world.hpp"

namespace trackphys {

/// How a field of autopilots races.
struct RaceSettings {
    /// Target speeds on straights (km/h): the pole car has the slowest, the last car of the
    /// grid the fastest, the others spread evenly between, so the field overtakes.
    double slowest_kmh = 420.0;
    double fastest_kmh = 600.0;
    /// The two lanes are this far (m) left and right of the centreline, the grid's
    /// columns: a car keeps to the lane of its column and moves to the other one to pass.
    double lane_offset = 2.5;
    /// A lane is blocked by a slower car in it (within lane_width of its line) from a few
    /// metres behind (alongside) to pass_look_ahead ahead along the track (m).
    double pass_look_ahead = 60.0;
    double lane_width = 2.5;
    /// A car lifts off closer than this (m) behind the car ahead in its lane, unless that
    /// one pulls away, and brakes in proportion to how fast it closes in.
    double follow_gap = 20.0;
    RaceGridSettings grid;
};

/// A field of cars racing laps of a generated track: a starting grid (race_grid), one
/// Autopilot per car with its own target speed, and a lane per car, chosen every update
/// from the field: its own lane, or the other one when a slower car is ahead in its own
/// and none in the other (else it stays, and lifts off behind the car ahead, which it may
/// still bump under braking). Everything
/// it decides is a function of the cars' states and the autopilots' progress, so a race
/// is as deterministic as its World.
///
/// Laps: the grid stands behind the start line, so a car's first crossing starts its lap
/// 1 (a flying start); laps(i) counts the crossings after it.
class TRACKPHYS_API RaceDrivers {
  public:
    /// Throws trackphys::Error for no cars, speeds that are not finite and > 0 or in the
    /// wrong order, or negative lane distances.
    RaceDrivers(const Track& track, const CarSpec& car, std::size_t cars,
                RaceSettings settings = {});

    /// Adds the field to `world` (which must hold no cars yet) on the grid.
    void add_cars(World& world) const;
    /// Sets every car's inputs for the next World::update.
    void drive(World& world);
    /// Call after each World::update: counts the laps each car completed in it, timed at
    /// world.time().
    void after_update(const World& world);

    std::size_t car_count() const { return pilots_.size(); }
    int laps(std::size_t car) const;
    /// Fewest laps completed by any car.
    int fewest_laps() const;
    /// Car i's lap times (s), one per completed lap.
    const std::vector<double>& lap_times(std::size_t car) const { return lap_times_.at(car); }
    /// Car i's target speed on straights (m/s).
    double target_speed(std::size_t car) const { return target_speeds_.at(car); }
    const Autopilot& autopilot(std::size_t car) const { return pilots_.at(car); }

    /// The autopilots' progress, to save beside a world snapshot, and back.
    std::vector<AutopilotProgress> progress() const;
    void set_progress(std::span<const AutopilotProgress> progress);

  private:
    // Where a car is across the road (m left of the centreline) and along it (m from the
    // start line), at its autopilot's nearest sample.
    struct RoadPosition {
        double across;
        double along;
    };
    RoadPosition road_position(const World& world, std::size_t car) const;
    // Car i's lane for the next update (m left of the centreline).
    double lane(const World& world, std::size_t i) const;
    // The nearest car ahead of car i within lane_width of `line`, from `from` m (negative:
    // behind, alongside) to pass_look_ahead m along the track: how far ahead (m, infinite
    // for none) and how fast car i closes in on it (m/s).
    struct CarAhead {
        double gap;
        double closing;
    };
    CarAhead car_ahead(const World& world, std::size_t i, double line, double from) const;

    const Track* track_;
    CarSpec car_;
    RaceSettings settings_;
    std::vector<Autopilot> pilots_;
    std::vector<double> target_speeds_;
    std::vector<double> lanes_;                   // this update's, chosen before any is set
    std::vector<std::vector<double>> lap_times_;  // per car
    std::vector<double> last_crossing_;           // per car: time of its last crossing (s)
};

}  // namespace trackphys
