#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "trackphys/world/race_drivers.hpp"

namespace trackphys::detail {

/// Which cars RaceDrivers' lane rules ask about: the nearest car ahead of car i whose
/// across lies within `width` of `line`, from `from` m (negative: behind, alongside) to
/// `look_ahead` m along a loop of `length` m.
struct LaneQuery {
    double line;
    double width;
    double from;
    double look_ahead;
    double length;
};

/// The nearest car of a LaneQuery: `car` is the asking car and `gap` infinite for none.
struct CarInLane {
    std::size_t car;
    double gap;
};

/// How far a car at `other` (m from the start line) is ahead of one at `me`, wrapped into
/// [from, length + from): the lane rules' own arithmetic, the same bits wherever it runs.
double gap_along(double me, double other, double from, double length);

/// `order` becomes every car's index, by along (then index): a field in track order.
void order_along_track(std::span<const RoadPosition> positions, std::vector<std::uint32_t>& order);

/// Car `car` moved along from `old_along` to positions[car].along: it moves to its new place
/// in `order`, past the cars it passed (usually none: a car moves a sample at most between
/// two readings).
void reorder_moved_car(std::span<const RoadPosition> positions, std::span<std::uint32_t> order,
                       std::size_t car, double old_along);

/// The nearest car ahead of car i in a lane, from the field in track order: the car of least
/// gap_along within the lane, of the least index among equal gaps, as a scan of every car
/// would find it. The gap rises with along except where it wraps, so the field splits into
/// at most four runs of rising gap (found by bisection); each is read from its start until
/// a car in the lane is passed: O(log cars) plus the cars skipped outside the lane.
/// `from` must be within a lap of 0 (|from| < length).
CarInLane nearest_car_ahead(std::span<const RoadPosition> positions,
                            std::span<const std::uint32_t> order, std::size_t i,
                            const LaneQuery& query);

}  // namespace trackphys::detail
