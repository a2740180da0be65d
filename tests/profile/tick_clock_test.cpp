#include "profile/tick_clock.hpp"

#include <algorithm>
#include <cmath>
#include <thread>

#include <gtest/gtest.h>

namespace trackphys {
namespace {

// The ticks a sleep took, turned into microseconds, against the microseconds steady_clock
// saw; the best of a few tries, as a busy machine can switch the thread out between the
// two clocks' readings.
TEST(TickClock, TicksTurnIntoTheTimeSteadyClockMeasures) {
    const double rate = TickClock::microseconds_per_tick();
    ASSERT_GT(rate, 0.0);
    double best_error = 1.0;
    for (int attempt = 0; attempt < 5 && best_error > 0.005; ++attempt) {
        const std::uint64_t ticks_before = TickClock::now();
        const TickClock::Steady::time_point before = TickClock::Steady::now();
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
        const std::uint64_t ticks_after = TickClock::now();
        const TickClock::Steady::time_point after = TickClock::Steady::now();
        ASSERT_GT(ticks_after, ticks_before);
        const double steady_us = std::chrono::duration<double, std::micro>(after - before).count();
        const double ticks_us = static_cast<double>(ticks_after - ticks_before) * rate;
        best_error = std::min(best_error, std::abs(ticks_us / steady_us - 1.0));
    }
    EXPECT_LT(best_error, 0.005);
}

}  // namespace
}  // namespace trackphys
