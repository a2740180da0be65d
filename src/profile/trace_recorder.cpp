#include "trackphys/profile/trace_recorder.hpp"

#include <cinttypes>
#include <cstdio>
#include <ostream>

namespace trackphys {

TraceRecorder::TraceRecorder(std::size_t max_events)
    : epoch_(Clock::now()), max_events_(max_events) {}

void TraceRecorder::record(const char* name, Clock::time_point begin, Clock::time_point end,
                           std::uint32_t thread) {
    if (events_.size() >= max_events_) {
        ++dropped_;
        return;
    }
    using std::chrono::duration_cast;
    using std::chrono::nanoseconds;
    events_.push_back({name, duration_cast<nanoseconds>(begin - epoch_).count(),
                       duration_cast<nanoseconds>(end - begin).count(), thread});
}

void TraceRecorder::write_chrome_trace(std::ostream& out) const {
    out << "{\"displayTimeUnit\":\"ns\",\"traceEvents\":[";
    char line[256];
    for (std::size_t i = 0; i < events_.size(); ++i) {
        const Event& e = events_[i];
        // Zone names are identifiers from the code (no quotes or backslashes to escape).
        std::snprintf(line, sizeof line,
                      "%s\n{\"name\":\"%s\",\"ph\":\"X\",\"pid\":1,\"tid\":%" PRIu32
                      ",\"ts\":%.3f,\"dur\":%.3f}",
                      i ? "," : "", e.name, e.thread, static_cast<double>(e.begin_ns) * 1e-3,
                      static_cast<double>(e.duration_ns) * 1e-3);
        out << line;
    }
    out << "\n]}\n";
}

}  // namespace trackphys
