#pragma once

#include <chrono>
#include <cstdint>

#if defined(__x86_64__)
#include <x86intrin.h>
#endif

namespace trackphys {

/// The clock the phase profile reads. A car's update reads it a few hundred times, and a
/// read of the x86 time-stamp counter costs a fraction of steady_clock's (docs/benchmarks.md,
/// "The profile's clock"). Elsewhere the ticks are steady_clock's own nanoseconds.
///
/// Ticks become microseconds through a rate measured once against steady_clock, over a
/// millisecond at the first call that asks for it. That needs a counter that runs at one
/// rate on every core ("invariant TSC", as current x86-64 CPUs have).
class TickClock {
  public:
    using Steady = std::chrono::steady_clock;

    static std::uint64_t now() noexcept {
#if defined(__x86_64__)
        return __rdtsc();
#else
        return static_cast<std::uint64_t>(
            std::chrono::duration_cast<std::chrono::nanoseconds>(Steady::now().time_since_epoch())
                .count());
#endif
    }

    static double microseconds_per_tick();
};

}  // namespace trackphys
