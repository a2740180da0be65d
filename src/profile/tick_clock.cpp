#include "profile/tick_clock.hpp"

namespace trackphys {
#if defined(__x86_64__)
namespace {

// A reading of both clocks at one instant, to within `spread` ticks.
struct ClockPair {
    std::uint64_t ticks;
    TickClock::Steady::time_point steady;
    std::uint64_t spread;
};

ClockPair read_both() {
    const std::uint64_t before = TickClock::now();
    const TickClock::Steady::time_point steady = TickClock::Steady::now();
    const std::uint64_t after = TickClock::now();
    return {before + (after - before) / 2, steady, after - before};
}

// The tightest of a few readings: a thread switched out between the two clocks would
// otherwise skew the rate by the time it was away.
ClockPair read_both_tightly() {
    ClockPair best = read_both();
    for (int attempt = 0; attempt < 8; ++attempt) {
        const ClockPair pair = read_both();
        if (pair.spread < best.spread) best = pair;
    }
    return best;
}

double measure_microseconds_per_tick() {
    const ClockPair start = read_both_tightly();
    while (TickClock::Steady::now() - start.steady < std::chrono::milliseconds(1)) {}
    const ClockPair end = read_both_tightly();
    const double us = std::chrono::duration<double, std::micro>(end.steady - start.steady).count();
    return us / static_cast<double>(end.ticks - start.ticks);
}

}  // namespace
#endif

double TickClock::microseconds_per_tick() {
#if defined(__x86_64__)
    static const double measured = measure_microseconds_per_tick();
    return measured;
#else
    return 1e-3;  // the ticks are steady_clock's nanoseconds
#endif
}

}  // namespace trackphys
