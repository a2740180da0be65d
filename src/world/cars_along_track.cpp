#include "world/cars_along_track.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "trackphys/assert.hpp"

namespace trackphys::detail {
namespace {

// std::fmod(x, length), for a length > 0, without fmod's cost where |x| < 2 length (the
// gap between two places on the loop): |x| - length is exact there (Sterbenz), as fmod
// is, and takes x's sign as fmod's result does (-0 for x = -length).
double remainder_toward_zero(double x, double length) {
    if (std::abs(x) < length) return x;
    if (std::abs(x) < 2.0 * length) return std::copysign(std::abs(x) - length, x);
    return std::fmod(x, length);
}

// Which of gap_along's pieces an unwrapped gap d (other - me - from) falls in; within a
// piece the wrapped gap rises with d. With both places in [0, length) and |from| < length,
// |d| < 2 length: remainder_toward_zero's first two cases, split by sign, -length going
// with the piece above it (its remainder is -0, not added to).
int gap_piece(double d, double length) {
    if (d < -length) return 0;
    if (d < 0.0) return 1;
    if (d < length) return 2;
    return 3;
}

bool before(std::span<const RoadPosition> positions, std::uint32_t a, std::uint32_t b) {
    return positions[a].along < positions[b].along ||
           (positions[a].along == positions[b].along && a < b);
}

}  // namespace

double gap_along(double me, double other, double from, double length) {
    double gap = remainder_toward_zero(other - me - from, length);
    if (gap < 0.0) gap += length;
    gap += from;
    return gap;
}

void order_along_track(std::span<const RoadPosition> positions, std::vector<std::uint32_t>& order) {
    order.resize(positions.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = static_cast<std::uint32_t>(i);
    std::sort(order.begin(), order.end(),
              [&](std::uint32_t a, std::uint32_t b) { return before(positions, a, b); });
}

void reorder_moved_car(std::span<const RoadPosition> positions, std::span<std::uint32_t> order,
                       std::size_t car, double old_along) {
    // Find the car at its old place: the order is by its old along and the others' own.
    const auto old_key_before = [&](std::uint32_t j, std::size_t) {
        const double along = j == car ? old_along : positions[j].along;
        return along < old_along || (along == old_along && j < car);
    };
    std::size_t at = static_cast<std::size_t>(
        std::lower_bound(order.begin(), order.end(), car, old_key_before) - order.begin());
    TP_ASSERT(at < order.size() && order[at] == car, "reorder_moved_car: car not at its old place");
    const auto id = static_cast<std::uint32_t>(car);
    while (at + 1 < order.size() && before(positions, order[at + 1], id)) {
        std::swap(order[at], order[at + 1]);
        ++at;
    }
    while (at > 0 && before(positions, id, order[at - 1])) {
        std::swap(order[at], order[at - 1]);
        --at;
    }
}

CarInLane nearest_car_ahead(std::span<const RoadPosition> positions,
                            std::span<const std::uint32_t> order, std::size_t i,
                            const LaneQuery& query) {
    TP_ASSERT(std::abs(query.from) < query.length, "nearest_car_ahead: from beyond a lap");
    const double me = positions[i].along;
    const auto unwrapped = [&](std::uint32_t j) { return positions[j].along - me - query.from; };
    CarInLane nearest{i, std::numeric_limits<double>::infinity()};
    auto run_begin = order.begin();
    for (int piece = 0; piece < 4; ++piece) {
        const auto run_end = std::partition_point(run_begin, order.end(), [&](std::uint32_t j) {
            return gap_piece(unwrapped(j), query.length) <= piece;
        });
        for (auto at = run_begin; at != run_end; ++at) {
            const std::uint32_t j = *at;
            const double gap = gap_along(me, positions[j].along, query.from, query.length);
            // The rest of the run is no nearer; a car as near may still have a lower index.
            if (gap > query.look_ahead || gap > nearest.gap) break;
            if (j == i || std::abs(positions[j].across - query.line) > query.width) continue;
            if (gap < nearest.gap || j < nearest.car) nearest = {j, gap};
        }
        run_begin = run_end;
    }
    return nearest;
}

}  // namespace trackphys::detail
