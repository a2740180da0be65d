#include "trackphys/world/race_drivers.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <sstream>
#include <string>

#include <glm/geometric.hpp>

#include "trackphys/error.hpp"
#include "world/cars_along_track.hpp"

namespace trackphys {
namespace {

constexpr double kMirror = -20.0;  // m: a lane change looks this far back

// The drivers' own copy of what they read of a track, its centreline and length: the
// caller's track need not outlive them, and its meshes are not copied.
std::shared_ptr<const Track> route_of(const Track& track) {
    auto route = std::make_shared<Track>();
    route->length_m = track.length_m;
    route->centerline = track.centerline;
    return route;
}

}  // namespace

AutopilotSettings race_autopilot() {
    AutopilotSettings driver;
    driver.lookahead_min = 6.0;
    driver.lookahead_time = 0.2;
    return driver;
}

RaceDrivers::RaceDrivers(const Track& track, const CarSpec& car, std::size_t cars,
                         RaceSettings settings)
    : route_(route_of(track)), car_(car), settings_(settings) {
    if (cars == 0) throw Error("RaceDrivers: a race needs at least one car");
    if (!(std::isfinite(settings_.slowest_kmh) && settings_.slowest_kmh > 0.0 &&
          std::isfinite(settings_.fastest_kmh) && settings_.fastest_kmh >= settings_.slowest_kmh))
        throw Error("RaceSettings: speeds must be finite and 0 < slowest_kmh <= fastest_kmh");
    if (!(std::isfinite(settings_.least_grip_use) && settings_.least_grip_use > 0.0 &&
          std::isfinite(settings_.most_grip_use) &&
          settings_.most_grip_use >= settings_.least_grip_use))
        throw Error(
            "RaceSettings: grip shares must be finite and 0 < least_grip_use <= most_grip_use");
    if (!(settings_.lane_offset >= 0.0 && settings_.pass_look_ahead >= 0.0 &&
          settings_.lane_width >= 0.0 && settings_.merge_gap >= 0.0 &&
          settings_.follow_distance >= 0.0 && settings_.follow_time >= 0.0 &&
          settings_.pass_closing >= 0.0 && settings_.swerve_turn_accel >= 0.0))
        throw Error(
            "RaceSettings: lane_offset, pass_look_ahead, lane_width, merge_gap, follow_distance, "
            "follow_time, pass_closing and swerve_turn_accel must be >= 0");
    if (!(settings_.merge_gap <= settings_.pass_look_ahead)) {
        std::ostringstream why;
        why << "RaceSettings: merge_gap (" << exact_text(settings_.merge_gap)
            << " m) must be <= pass_look_ahead (" << exact_text(settings_.pass_look_ahead)
            << " m), as far as the lanes are read";
        throw Error(why.str());
    }
    if (!(std::isfinite(settings_.lane_change_speed) && settings_.lane_change_speed > 0.0))
        throw Error("RaceSettings: lane_change_speed must be finite and > 0");
    if (!(settings_.rescue_distance > 0.0))
        throw Error("RaceSettings: rescue_distance must be > 0 (infinity: never rescue)");
    // The lane rules keep the field in track order (cars_along_track.hpp), which holds only
    // for places along the track in [0, length_m): read_track checks a map's track, a track
    // built by hand is checked here.
    if (!(std::isfinite(track.length_m) && track.length_m > -kMirror))
        throw Error("RaceDrivers: the track's length must be finite and > " + exact_text(-kMirror) +
                    " m (a lane change looks that far back), got " + exact_text(track.length_m) +
                    " m");
    for (const CenterlineSample& sample : track.centerline)
        if (!(sample.distance >= 0.0 && sample.distance < track.length_m)) {
            std::ostringstream why;
            why << "RaceDrivers: a centreline sample at " << sample.distance
                << " m along the track is outside [0, " << track.length_m << ") m";
            throw Error(why.str());
        }
    // One copy of the centreline for the whole field.
    const std::shared_ptr<const std::vector<CenterlineSample>> centerline(route_,
                                                                          &route_->centerline);
    for (std::size_t i = 0; i < cars; ++i) {
        const double share =
            cars == 1 ? 0.0 : static_cast<double>(i) / static_cast<double>(cars - 1);
        AutopilotSettings driver = settings_.driver;
        driver.target_speed =
            (settings_.slowest_kmh + share * (settings_.fastest_kmh - settings_.slowest_kmh)) / 3.6;
        driver.grip_use =
            settings_.least_grip_use + share * (settings_.most_grip_use - settings_.least_grip_use);
        pilots_.emplace_back(centerline, track.length_m, car, driver);
    }
    for (std::size_t i = 0; i < cars; ++i) progress_.lanes.push_back(own_lane(i));
    progress_.lines = progress_.lanes;
    progress_.lap_times.resize(cars);
    progress_.last_crossings.assign(cars, 0.0);
    progress_.rescues.assign(cars, 0);
    next_lanes_.assign(cars, 0.0);
    road_positions_.resize(cars);
}

double RaceDrivers::own_lane(std::size_t car) const {
    // Even grid places are in the left column.
    return car % 2 == 0 ? settings_.lane_offset : -settings_.lane_offset;
}

void RaceDrivers::add_cars(World& world) const {
    if (world.car_count() != 0) throw Error("RaceDrivers::add_cars: the world has cars already");
    for (const RigidBodyState& start :
         race_grid(*route_, world.statics(), car_, pilots_.size(), settings_.grid))
        world.add_car(car_, start);
}

RaceDrivers::RoadPosition RaceDrivers::road_position(const World& world, std::size_t car) const {
    const CenterlineSample& s = route_->centerline[pilots_[car].nearest_sample()];
    const glm::dvec3 offset = world.car(car).state().position - s.position;
    return RoadPosition{glm::dot(offset, s.left), s.distance};
}

RaceDrivers::CarAhead RaceDrivers::car_ahead(const World& world, std::size_t i, double line,
                                             double from) const {
    const detail::CarInLane nearest = detail::nearest_car_ahead(
        road_positions_, cars_along_, i,
        {line, settings_.lane_width, from, settings_.pass_look_ahead, route_->length_m});
    const std::size_t j = nearest.car;
    if (j == i) return {i, nearest.gap, 0.0};
    const glm::dvec3 toward = world.car(j).state().position - world.car(i).state().position;
    const double distance = glm::length(toward);
    const glm::dvec3 relative =
        world.car(i).state().linear_velocity - world.car(j).state().linear_velocity;
    return {j, nearest.gap, distance > 0.0 ? glm::dot(relative, toward) / distance : 0.0};
}

bool RaceDrivers::slower(std::size_t i, const CarAhead& ahead, double closing) const {
    return std::isfinite(ahead.gap) &&
           (ahead.closing > closing || grip_use(ahead.car) < grip_use(i));
}

double RaceDrivers::lane(const World& world, std::size_t i) const {
    constexpr double kAlongside = -6.0;  // m: a car this far behind is still beside us
    const double own = own_lane(i);
    const double current = progress_.lanes[i];
    // A swerve turned back halfway, as the lanes' cars change their minds, sways the car
    // from side to side, and at speed in a turn the sway grows into a slide.
    if (progress_.lines[i] != current) return current;
    // Nor does a swerve begin in a fast turn: it adds its own sideways push to the turn's,
    // and a car near the limit slides.
    const CenterlineSample& here = route_->centerline[pilots_[i].nearest_sample()];
    const double speed = world.car(i).speed();
    if (speed * speed * std::abs(here.curvature) > settings_.swerve_turn_accel) return current;
    // Blocked: the car ahead in the lane closes in faster than `closing`, or has the
    // slower pace.
    const auto blocked = [&](double line, double closing) {
        return slower(i, car_ahead(world, i, line, kAlongside), closing);
    };
    // Free: nobody from kMirror behind to merge_gap ahead, and the car ahead (if any) not
    // closing in.
    const auto free = [&](double line) {
        const CarAhead nearest = car_ahead(world, i, line, kMirror);
        return !(nearest.gap < settings_.merge_gap) && !(nearest.closing > 0.0);
    };
    // Out to pass when its own lane is blocked, back once its own lane is free and no
    // longer blocked at all: a car that came back behind the car it pulled out for would
    // only pull out again, and a closing speed that flickers about pass_closing must not
    // send a car out and back.
    if (current == own) return blocked(own, settings_.pass_closing) && free(-own) ? -own : own;
    return free(own) && !blocked(own, 0.0) ? own : -own;
}

double RaceDrivers::line_towards(std::size_t i, double lane, double dt) const {
    const double step = settings_.lane_change_speed * dt;
    return std::clamp(lane, progress_.lines[i] - step, progress_.lines[i] + step);
}

double RaceDrivers::following_speed(const CarAhead& ahead, double speed) const {
    // Each metre off the following distance asks 1 m/s more or less than the car ahead's.
    constexpr double kGapRate = 1.0;  // 1/s
    // Never slower: a car stopped behind a stopped car (after a crash) would wait for ever;
    // crawling, it bumps it or passes it.
    constexpr double kCrawling = 5.0;  // m/s
    if (!std::isfinite(ahead.gap)) return std::numeric_limits<double>::infinity();
    const double keep = settings_.follow_distance + settings_.follow_time * speed;
    return std::max(speed - ahead.closing + kGapRate * (ahead.gap - keep), kCrawling);
}

void RaceDrivers::check_field(const World& world, const char* caller) const {
    if (world.car_count() != pilots_.size())
        throw Error(std::string(caller) + ": the world has " + std::to_string(world.car_count()) +
                    " cars, the race " + std::to_string(pilots_.size()) +
                    " (a race drives the field add_cars put in the world)");
}

void RaceDrivers::drive(World& world) {
    check_field(world, "RaceDrivers::drive");
    // Before the first update a pilot has not found its car: every car would read as
    // standing at the start line, and the grid would find nobody ahead.
    for (std::size_t i = 0; i < pilots_.size(); ++i)
        if (!pilots_[i].located()) pilots_[i].locate(world.car(i));
    // Where every car is, read once and put in track order: the lanes below look for the
    // cars near each car along the track.
    for (std::size_t i = 0; i < pilots_.size(); ++i) road_positions_[i] = road_position(world, i);
    detail::order_along_track(road_positions_, cars_along_);
    // Every lane from the same instant, before any car's inputs change.
    for (std::size_t i = 0; i < pilots_.size(); ++i) next_lanes_[i] = lane(world, i);
    const double dt = world.settings().dt_update;
    // Only a car in front: two cars side by side must not both slow down for each other.
    constexpr double kInFront = 1.0;  // m
    for (std::size_t i = 0; i < pilots_.size(); ++i) {
        progress_.lanes[i] = next_lanes_[i];
        progress_.lines[i] = line_towards(i, next_lanes_[i], dt);
        pilots_[i].set_lane_offset(progress_.lines[i]);
        // The car ahead on its line, or where it is now on its way there.
        CarAhead ahead = car_ahead(world, i, progress_.lines[i], kInFront);
        if (const CarAhead here = car_ahead(world, i, road_positions_[i].across, kInFront);
            here.gap < ahead.gap)
            ahead = here;
        Car& car = world.car(i);
        pilots_[i].set_speed_limit(following_speed(ahead, car.speed()));
        car.set_inputs(pilots_[i].drive(car));
        // Driving locates the car again. At the place after_update located it from, that is
        // nearly always the same sample, but the windowed search starts from its last answer
        // and may step on: the cars after i see car i where its pilot now puts it.
        const double along = road_positions_[i].along;
        road_positions_[i] = road_position(world, i);
        detail::reorder_moved_car(road_positions_, cars_along_, i, along);
    }
}

void RaceDrivers::after_update(World& world) {
    check_field(world, "RaceDrivers::after_update");
    for (std::size_t i = 0; i < pilots_.size(); ++i) {
        const int before = pilots_[i].laps();
        pilots_[i].locate(world.car(i));
        if (left_track(world, i)) rescue(world, i);
        if (pilots_[i].laps() <= before) continue;
        if (pilots_[i].laps() > 1)
            progress_.lap_times[i].push_back(world.time() - progress_.last_crossings[i]);
        progress_.last_crossings[i] = world.time();
    }
}

bool RaceDrivers::left_track(const World& world, std::size_t i) const {
    const CenterlineSample& s = route_->centerline[pilots_[i].nearest_sample()];
    return !(glm::distance(world.car(i).state().position, s.position) <= settings_.rescue_distance);
}

void RaceDrivers::rescue(World& world, std::size_t i) {
    // Clear of the others by about two car lengths: a car put down on top of another would
    // be thrown off again by the contact.
    constexpr double kClearance = 10.0;  // m
    const std::vector<CenterlineSample>& centerline = route_->centerline;
    const auto clear = [&](const glm::dvec3& spot) {
        for (std::size_t j = 0; j < pilots_.size(); ++j)
            if (j != i && glm::distance(world.car(j).state().position, spot) < kClearance)
                return false;
        return true;
    };
    const double lane = own_lane(i);
    std::size_t at = pilots_[i].nearest_sample();
    for (std::size_t tried = 0; tried < centerline.size(); ++tried) {
        const CenterlineSample& s = centerline[at];
        if (clear(s.position + s.left * lane)) break;
        at = (at + 1) % centerline.size();
    }
    const CenterlineSample& s = centerline[at];
    RigidBodyState state = place_car_on_track(world.statics(), car_, s, lane);
    state.linear_velocity = s.tangent * pilots_[i].planned_speed(at);
    world.car(i).set_state(state);
    pilots_[i].locate(world.car(i));
    progress_.lanes[i] = lane;
    progress_.lines[i] = lane;
    ++progress_.rescues[i];
}

int RaceDrivers::laps(std::size_t car) const {
    return std::max(0, autopilot(car, "RaceDrivers::laps").laps() - 1);
}

std::size_t RaceDrivers::checked(std::size_t car, const char* caller) const {
    if (car >= pilots_.size())
        throw Error(std::string(caller) + ": no car " + std::to_string(car) + ": the race has " +
                    std::to_string(pilots_.size()) + (pilots_.size() == 1 ? " car" : " cars"));
    return car;
}

int RaceDrivers::fewest_laps() const {
    int fewest = laps(0);
    for (std::size_t i = 1; i < pilots_.size(); ++i) fewest = std::min(fewest, laps(i));
    return fewest;
}

RaceProgress RaceDrivers::progress() const {
    RaceProgress all = progress_;
    for (const Autopilot& pilot : pilots_) all.pilots.push_back(pilot.progress());
    return all;
}

void RaceDrivers::set_progress(const RaceProgress& progress) {
    const std::size_t n = pilots_.size();
    if (progress.pilots.size() != n || progress.lanes.size() != n || progress.lines.size() != n ||
        progress.lap_times.size() != n || progress.last_crossings.size() != n ||
        progress.rescues.size() != n)
        throw Error("RaceDrivers::set_progress: the progress is not of a field of " +
                    std::to_string(n) + " cars");
    // Every pilot's checked before any is set: a refused progress changes nothing.
    for (std::size_t i = 0; i < n; ++i) pilots_[i].check_progress(progress.pilots[i]);
    for (std::size_t i = 0; i < n; ++i) pilots_[i].set_progress(progress.pilots[i]);
    progress_ = progress;
    progress_.pilots.clear();
}

}  // namespace trackphys
