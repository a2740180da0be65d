#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "trackphys/world/world.hpp"

namespace trackphys::cli {

/// Stops drive and race when a car is reset at every update: a car spec that validation
/// cannot catch (an ellipsoid of 500 m semi-axes, deep in the track wherever it stands)
/// would otherwise run on for the whole drive, put back at every update, and exit 0.
class ResetStreak {
  public:
    /// A run of this many updates, each of which reset the car, stops the command.
    static constexpr std::uint64_t kLimit = 10;

    explicit ResetStreak(const World& world);

    /// Call after every world.update() (and race's rescues). A car's resets are the World's
    /// (World::car_resets) plus rescues[i], the times race put it back on the track (empty:
    /// none). Throws trackphys::Error naming the car, the update and time its streak began,
    /// and why it was last reset, once a car has been reset at each of its last kLimit
    /// updates.
    void after_update(const World& world, std::span<const std::uint64_t> rescues = {});

  private:
    struct Car {
        std::uint64_t resets = 0;   ///< World::car_resets before this update
        std::uint64_t rescues = 0;  ///< rescues before this update
        std::uint64_t streak = 0;   ///< consecutive updates that reset it
        double since_s = 0.0;       ///< the simulated time when the streak's first update began
    };
    std::vector<Car> cars_;
    double previous_time_s_ = 0.0;
};

}  // namespace trackphys::cli
