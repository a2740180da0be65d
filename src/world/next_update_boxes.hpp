#pragma once

#include <cstddef>
#include <cstring>
#include <span>
#include <vector>

#include "trackphys/dynamics/car.hpp"
#include "trackphys/dynamics/rigid_body.hpp"
#include "trackphys/geometry/aabb.hpp"
#include "trackphys/world/world_settings.hpp"
#include "world/update_box.hpp"

namespace trackphys::detail {

/// Each car's next update box (car_update_box), computed at the end of the car's own
/// update, while its body ellipsoids are still in the cache of the core that ran it, and
/// kept with the bits of the state and suspension it came from. The update's serial part
/// then reads the car's state and suspension alone; a car whose bits changed in between
/// (set by the game, restored from a snapshot, reset, or never updated yet) gets its box
/// computed there, as before. The box is a function of those bits and of what never
/// changes (the spec, the settings), so the update is the same bit for bit either way.
class NextUpdateBoxes {
  public:
    /// Makes room for the next car the world added (cars are never removed), which has no
    /// box yet.
    void add_car(std::size_t ellipsoids) {
        Entry& entry = entries_.emplace_back();
        entry.suspension_at = suspension_.size();
        suspension_.resize(suspension_.size() + ellipsoids);
    }
    std::size_t car_count() const { return entries_.size(); }

    /// Computes car i's next box from its state now. Different cars' entries may be written
    /// from different threads at once.
    void remember(std::size_t i, const Car& car, const WorldSettings& settings) {
        Entry& entry = entries_[i];
        entry.box = car_update_box(car, settings);
        entry.state = car.state();
        const std::span<const double> suspension = car.suspension();
        std::memcpy(&suspension_[entry.suspension_at], suspension.data(), suspension.size_bytes());
        entry.known = true;
    }

    /// car_update_box(car, settings), for car i: the remembered box while the car still has
    /// the bits it was computed from, else computed now.
    Aabb box(std::size_t i, const Car& car, const WorldSettings& settings) const {
        const Entry& entry = entries_[i];
        const std::span<const double> suspension = car.suspension();
        if (entry.known && same_bits(entry.state, car.state()) &&
            std::memcmp(&suspension_[entry.suspension_at], suspension.data(),
                        suspension.size_bytes()) == 0)
            return entry.box;
        return car_update_box(car, settings);
    }

  private:
    struct Entry {
        Aabb box;
        RigidBodyState state;
        std::size_t suspension_at = 0;  // where its copy of the suspension starts
        bool known = false;
    };

    // Bitwise, not ==: a -0.0 that became 0.0 may move a box's bound by its sign, and a
    // bit that compares equal must give the same box.
    static bool same_bits(const RigidBodyState& a, const RigidBodyState& b) {
        static_assert(sizeof(RigidBodyState) == 13 * sizeof(double), "no padding to compare");
        return std::memcmp(&a, &b, sizeof(RigidBodyState)) == 0;
    }

    std::vector<Entry> entries_;
    std::vector<double> suspension_;  // every car's copy, one after the other
};

}  // namespace trackphys::detail
