#include "trackphys/profile/trace_recorder.hpp"

#include <sstream>
#include <string>

#include <gtest/gtest.h>

namespace trackphys {
namespace {

TEST(TraceRecorder, WritesCompleteEventsAndDropsBeyondItsCapacity) {
    TraceRecorder trace(2);
    const auto t0 = TraceRecorder::Clock::now();
    trace.record("broad", t0, t0 + std::chrono::microseconds(5));
    { ScopedTraceZone zone(&trace, "update"); }
    trace.record("exact", t0, t0);  // over capacity
    EXPECT_EQ(trace.size(), 2u);
    EXPECT_EQ(trace.dropped(), 1u);

    std::ostringstream out;
    trace.write_chrome_trace(out);
    const std::string json = out.str();
    EXPECT_EQ(json.rfind("{\"displayTimeUnit\":\"ns\",\"traceEvents\":[", 0), 0u);
    EXPECT_NE(json.find("{\"name\":\"broad\",\"ph\":\"X\",\"pid\":1,\"tid\":0,"),
              std::string::npos);
    EXPECT_NE(json.find("\"dur\":5.000}"), std::string::npos);
    EXPECT_NE(json.find("\"name\":\"update\""), std::string::npos);
    EXPECT_EQ(json.find("exact"), std::string::npos);
    EXPECT_EQ(json.substr(json.size() - 4), "\n]}\n");
}

}  // namespace
}  // namespace trackphys
