#pragma once

#include <chrono>

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
          last_(enabled ? Clock::now() : Clock::time_point{}) {}

    /// The profile the laps go to, for the counts kept beside the times.
    UpdateProfile& profile() { return profile_; }

    void lap(Phase phase) {
        if (!enabled_) return;
        const Clock::time_point now = Clock::now();
        profile_[phase] += std::chrono::duration<double, std::micro>(now - last_).count();
        if (trace_) trace_->record(phase_name(phase), last_, now);
        last_ = now;
    }

  private:
    UpdateProfile& profile_;
    bool enabled_;
    TraceRecorder* trace_;
    Clock::time_point last_;
};

}  // namespace trackphys
