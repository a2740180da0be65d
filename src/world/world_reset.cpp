// The reset policy around each island's update (see World's class notes): where each car
// starts, the update, the hand-over of each car's worker scratch at its end (what its next
// update and debug_draw read), and the reset of every car that ended it impossible; and the
// same check of a state a game gave between updates.

#include <cstdint>
#include <exception>
#include <span>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "dynamics/car_access.hpp"
#include "profile/phase_stopwatch.hpp"
#include "trackphys/error.hpp"
#include "trackphys/math/types.hpp"
#include "trackphys/world/world.hpp"
#include "world/car_scratch.hpp"
#include "world/car_slot.hpp"
#include "world/update_work.hpp"

namespace trackphys {

std::string World::impossible_state(const RigidBodyState& s) const {
    // Once per car and update: the common case decides without building a message (a NaN or
    // infinite velocity fails the comparisons too).
    const double v = glm::length(s.linear_velocity);
    const double w = glm::length(s.angular_velocity);
    if (is_finite(s.position) && is_finite(s.orientation) && v <= settings_.max_car_speed &&
        w <= settings_.max_car_angular_speed)
        return {};
    // In the message, lengths whose squares overflow (a push of 1e300 N s) by their largest
    // component: "speed 1e+297 m/s", not "inf".
    const auto magnitude = [](const glm::dvec3& u) {
        const double largest = std::max({std::abs(u.x), std::abs(u.y), std::abs(u.z)});
        return largest > 0.0 ? largest * glm::length(u / largest) : 0.0;
    };
    std::ostringstream why;
    if (!is_finite(s.position))
        why << "position is not finite";
    else if (!is_finite(s.orientation))
        why << "orientation is not finite";
    else if (!is_finite(s.linear_velocity))
        why << "linear velocity is not finite";
    else if (!is_finite(s.angular_velocity))
        why << "angular velocity is not finite";
    else if (!(v <= settings_.max_car_speed))
        why << "speed " << exact_text(magnitude(s.linear_velocity))
            << " m/s is above WorldSettings.max_car_speed " << exact_text(settings_.max_car_speed);
    else
        why << "angular speed " << exact_text(magnitude(s.angular_velocity))
            << " rad/s is above WorldSettings.max_car_angular_speed "
            << exact_text(settings_.max_car_angular_speed);
    return why.str();
}

namespace {

// A reset car touches nothing of its undone update, as its road contacts are cleared: its
// pairs that were touching end, and a touch still there begins again at the next update.
void undo_touches(const detail::CarIslands& islands, detail::CarTouches& touches,
                  std::size_t island, std::uint32_t car) {
    const std::span<const detail::CarPair> pairs = islands.pairs(island);
    for (std::size_t p = 0; p < pairs.size(); ++p)
        if (pairs[p].a == car || pairs[p].b == car) touches.undo(islands.first_pair(island) + p);
}

}  // namespace

// The hook around the hot loop: remember where each car of the island starts, run the
// update, and reset every car that ended it impossible. A car whose state turns non-finite
// mid-update makes a query of the update throw (non-finite shapes are rejected there);
// that is the same impossible state, caught and reset here. Any other error, with every
// car's state still possible, propagates.
void World::update_island_or_reset(std::size_t island, WorkerScratch& scratch,
                                   PhaseStopwatch& watch) {
    const std::span<const std::uint32_t> cars = work_->islands.cars(island);
    for (const std::uint32_t i : cars) {
        CarSlot& slot = cars_[i];
        slot.start_state = slot.car.state();
        const std::span<const double> suspension = slot.car.suspension();
        slot.start_suspension.assign(suspension.begin(), suspension.end());
    }
    std::exception_ptr stopped;
    std::string stop_reason;
    try {
        step_island(island, scratch, watch);
    } catch (const Error& error) {
        stopped = std::current_exception();
        stop_reason = std::string(" (the update stopped: ") + error.what() + ")";
    }
    scratch.grow_alike(cars.size());
    bool reset_any = false;
    for (const std::uint32_t i : cars) {
        CarSlot& slot = cars_[i];
        // The worker's scratch belongs to its next car now: keep what the car's next update
        // and debug_draw need of it.
        if (slot.scratch) {
            slot.empty_lists = slot.scratch->empty_lists();
            slot.drawn.take(*slot.scratch);
        }
        slot.scratch = nullptr;
        const std::string why = impossible_state(slot.car.state());
        if (why.empty()) continue;
        reset_any = true;
        reset_at_rest(slot, slot.start_state, slot.start_suspension,
                      "update " + std::to_string(updates_ + 1) + ": " + why + stop_reason);
        slot.start_hits();  // hits of an undone update
        undo_touches(work_->islands, work_->touches, island, i);
    }
    if (stopped && !reset_any) std::rethrow_exception(stopped);
}

// A car a game made impossible between updates (Car::set_state or apply_impulse with a
// finite but absurd velocity) would make its update box, and so the broad phase of every
// car, infinite: it is reset at rest where it is, before the broad phase.
void World::reset_impossible_starts() {
    for (CarSlot& slot : cars_) {
        const std::string why = impossible_state(slot.car.state());
        if (why.empty()) continue;
        const std::span<const double> suspension = slot.car.suspension();
        reset_at_rest(slot, slot.car.state(),
                      std::vector<double>(suspension.begin(), suspension.end()),
                      "before update " + std::to_string(updates_ + 1) + ": " + why +
                          " (a state given since the last update: Car::set_state, "
                          "Car::apply_impulse)");
    }
}

void World::reset_at_rest(CarSlot& slot, RigidBodyState at, std::span<const double> suspension,
                          std::string reason) {
    at.linear_velocity = glm::dvec3(0.0);
    at.angular_velocity = glm::dvec3(0.0);
    // Car::restore re-checks the state: if even that were impossible it throws, loudly.
    detail::CarAccess::restore(slot.car, at, slot.car.inputs(), suspension);
    if (const Vehicle* vehicle = slot.car.vehicle()) slot.car.set_vehicle_state(vehicle->at_rest());
    slot.forget_contacts();
    ++slot.resets;
    slot.last_reset = std::move(reason);
}

}  // namespace trackphys
