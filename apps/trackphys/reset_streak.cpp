#include "reset_streak.hpp"

#include <cstdio>
#include <string>

#include "trackphys/error.hpp"

namespace trackphys::cli {

ResetStreak::ResetStreak(const World& world)
    : cars_(world.car_count()), previous_time_s_(world.time()) {
    for (std::size_t i = 0; i < cars_.size(); ++i) cars_[i].resets = world.car_resets(i);
}

void ResetStreak::after_update(const World& world, std::span<const std::uint64_t> rescues) {
    for (std::size_t i = 0; i < cars_.size(); ++i) {
        Car& car = cars_[i];
        const std::uint64_t resets = world.car_resets(i);
        const std::uint64_t rescued = rescues.empty() ? 0 : rescues[i];
        const bool by_the_world = resets != car.resets;
        if (!by_the_world && rescued == car.rescues) {
            car.streak = 0;
            continue;
        }
        car.resets = resets;
        car.rescues = rescued;
        if (car.streak++ == 0) car.since_s = previous_time_s_;
        if (car.streak < kLimit) continue;
        char text[160];
        std::snprintf(text, sizeof text,
                      "car %zu was reset at every one of its last %llu updates, since %.2f s "
                      "simulated (update %llu)",
                      i, static_cast<unsigned long long>(car.streak), car.since_s,
                      static_cast<unsigned long long>(world.update_count() - car.streak + 1));
        throw Error(std::string(text) + ": its car spec cannot drive here; the last reset: " +
                    (by_the_world ? world.last_reset_reason(i)
                                  : std::string("rescued, it had left the track")));
    }
    previous_time_s_ = world.time();
}

}  // namespace trackphys::cli
