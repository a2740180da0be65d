#pragma once

#include <algorithm>
#include <chrono>
#include <cstdint>

#include "profile/tick_clock.hpp"
#include "trackphys/profile/trace_recorder.hpp"
#include "trackphys/profile/update_profile.hpp"

namespace trackphys {

/// Splits elapsed wall-clock time between phases: each lap(phase) charges the time since
/// the previous lap to that phase, and records it as a zone when a trace is given.
/// Disabled, it never reads the clock, so profiling costs nothing when it is off.
class PhaseStopwatch {
  public:
    using Clock = std::chrono::steady_clock;

    PhaseStopwatch(UpdateProfile& profile, bool enabled, TraceRecorder* trace = nullptr)
        : profile_(profile),
          enabled_(enabled),
          trace_(enabled ? trace : nullptr),
          microseconds_per_tick_(enabled ? TickClock::microseconds_per_tick() : 0.0),
          last_(enabled ? TickClock::now() : 0),
          last_traced_(trace_ ? Clock::now() : Clock::time_point{}) {}

    /// The profile the laps go to, for the counts kept beside the times.
    UpdateProfile& profile() { return profile_; }

    void lap(Phase phase) {
        if (!enabled_) return;
        const std::uint64_t now = TickClock::now();
        // A thread moved to a core whose counter is a few ticks behind charges nothing.
        const auto elapsed = static_cast<std::int64_t>(now - last_);
        profile_[phase] +=
            static_cast<double>(std::max<std::int64_t>(elapsed, 0)) * microseconds_per_tick_;
        last_ = now;
        if (trace_) trace_zone(phase);
    }

  private:
    // Traces read steady_clock itself: ticks turned into time would drift from the update
    // zones World records, by the rate's error times the run's length.
    void trace_zone(Phase phase) {
        const Clock::time_point now = Clock::now();
        trace_->record(phase_name(phase), last_traced_, now);
        last_traced_ = now;
    }

    UpdateProfile& profile_;
    bool enabled_;
    TraceRecorder* trace_;
    double microseconds_per_tick_;
    std::uint64_t last_;
    Clock::time_point last_traced_;
};

}  // namespace trackphys
