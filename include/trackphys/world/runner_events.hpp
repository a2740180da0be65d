#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "trackphys/world/contact_events.hpp"

namespace trackphys {

/// An event of a PhysicsRunner's world and the update it happened in.
template <class Event>
struct StampedEvent {
    std::uint64_t update = 0;  ///< the world's update_count() once that update had run
    Event event;
};

/// A car the world's reset policy put back (see World's class notes): one event a car and
/// update, with the update's last reason, also when the car was reset twice in it (before
/// the update and at its end; World::car_resets counts both).
struct CarResetEvent {
    std::uint32_t car = 0;  ///< the runner's number
    std::string reason;     ///< World::last_reset_reason
};

/// What a PhysicsRunner's world reported over the updates since the game last took it
/// (PhysicsRunner::take_events): the contact events as World::contact_events gives them
/// after each update, and the cars reset, each stamped with its update, in update order and
/// within an update in World's order. Car numbers are the runner's (World's indices shift
/// down past a removed car; the runner's do not).
struct RunnerEvents {
    std::vector<StampedEvent<CarTouchBeginEvent>> car_touch_begins;
    std::vector<StampedEvent<CarTouchEndEvent>> car_touch_ends;
    std::vector<StampedEvent<BodyHitEvent>> body_hits;
    std::vector<StampedEvent<CarResetEvent>> resets;

    bool empty() const {
        return car_touch_begins.empty() && car_touch_ends.empty() && body_hits.empty() &&
               resets.empty();
    }
    /// Empties every list, keeping its capacity.
    void clear() {
        car_touch_begins.clear();
        car_touch_ends.clear();
        body_hits.clear();
        resets.clear();
    }
};

}  // namespace trackphys
