#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <iosfwd>
#include <vector>

#include "trackphys/export.hpp"

namespace trackphys {

/// Records timed zones and writes them as a Chrome trace (JSON "traceEvents" of complete
/// "X" events), which chrome://tracing and ui.perfetto.dev open. Zone names must be string
/// literals (or outlive the recorder). It keeps at most max_events zones and counts the
/// rest as dropped, so a long run cannot exhaust memory.
class TRACKPHYS_API TraceRecorder {
  public:
    using Clock = std::chrono::steady_clock;

    explicit TraceRecorder(std::size_t max_events = 2'000'000);

    /// Records the zone `name` from begin to end on the trace's row `thread` (the trace's
    /// "tid": any number that tells the threads apart, e.g. a worker's index).
    void record(const char* name, Clock::time_point begin, Clock::time_point end,
                std::uint32_t thread = 0);

    /// Zones recorded, at most max_events.
    std::size_t size() const { return events_.size(); }
    /// Zones not recorded because max_events were already.
    std::size_t dropped() const { return dropped_; }

    /// Writes the trace; timestamps are microseconds since the recorder was made.
    void write_chrome_trace(std::ostream& out) const;

  private:
    struct Event {                 // 32 bytes
        const char* name;          // 8
        std::int64_t begin_ns;     // 8, since epoch_
        std::int64_t duration_ns;  // 8
        std::uint32_t thread;      // 4 (+4 padding)
    };
    static_assert(sizeof(Event) == 32);

    Clock::time_point epoch_;
    std::size_t max_events_;
    std::size_t dropped_ = 0;
    std::vector<Event> events_;
};

/// Times the enclosing scope into a recorder (nothing when the recorder is null).
class ScopedTraceZone {
  public:
    ScopedTraceZone(TraceRecorder* recorder, const char* name)
        : recorder_(recorder),
          name_(name),
          begin_(recorder ? TraceRecorder::Clock::now() : TraceRecorder::Clock::time_point{}) {}
    ~ScopedTraceZone() {
        if (recorder_) recorder_->record(name_, begin_, TraceRecorder::Clock::now());
    }
    ScopedTraceZone(const ScopedTraceZone&) = delete;
    ScopedTraceZone& operator=(const ScopedTraceZone&) = delete;

  private:
    TraceRecorder* recorder_;
    const char* name_;
    TraceRecorder::Clock::time_point begin_;
};

}  // namespace trackphys
