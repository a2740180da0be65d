#include "trackphys/profile/profile_statistics.hpp"

#include <thread>

#include <gtest/gtest.h>

#include "profile/phase_stopwatch.hpp"

namespace trackphys {
namespace {

TEST(ProfileStatistics, SummaryUsesNearestRankPercentiles) {
    std::vector<double> values;
    for (int i = 100; i >= 1; --i) values.push_back(i);  // 1..100, unsorted
    const Summary s = summarize(values);
    EXPECT_DOUBLE_EQ(s.mean, 50.5);
    EXPECT_DOUBLE_EQ(s.p50, 50.0);
    EXPECT_DOUBLE_EQ(s.p99, 99.0);
    EXPECT_DOUBLE_EQ(s.max, 100.0);
    const Summary one = summarize({7.0});
    EXPECT_EQ(one.p50, 7.0);
    EXPECT_EQ(one.p99, 7.0);
    const Summary none = summarize({});
    EXPECT_EQ(none.max, 0.0);
}

TEST(ProfileStatistics, AveragesCountsPerUpdateAndPerEllipsoidSubstep) {
    ProfileStatistics stats;
    UpdateProfile a;
    a.update_us = 10.0;
    a[Phase::exact] = 4.0;
    a.candidates = 100;
    a.culled_tests = 3200;
    a.ellipsoid_substeps = 320;
    a.exact_tests = 50;
    a.contacts = 40;
    UpdateProfile b = a;
    b.update_us = 30.0;
    b[Phase::exact] = 8.0;
    b.candidates = 300;
    b.culled_tests = 6400;
    stats.add(a);
    stats.add(b);
    EXPECT_EQ(stats.updates(), 2u);
    EXPECT_DOUBLE_EQ(stats.update_us().mean, 20.0);
    EXPECT_DOUBLE_EQ(stats.phase_us(Phase::exact).max, 8.0);
    EXPECT_DOUBLE_EQ(stats.phase_us(Phase::broad).max, 0.0);
    EXPECT_DOUBLE_EQ(stats.mean_candidates(), 200.0);
    EXPECT_DOUBLE_EQ(stats.mean_tested_per_ellipsoid_substep(), 15.0);
    EXPECT_DOUBLE_EQ(stats.mean_contacts(), 40.0);
}

TEST(PhaseStopwatch, ChargesElapsedTimeToPhasesOnlyWhenEnabled) {
    UpdateProfile profile;
    {
        PhaseStopwatch watch(profile, true);
        std::this_thread::sleep_for(std::chrono::milliseconds(2));
        watch.lap(Phase::broad);
        watch.lap(Phase::mid);
    }
    EXPECT_GE(profile[Phase::broad], 2000.0);
    EXPECT_LT(profile[Phase::mid], profile[Phase::broad]);

    UpdateProfile untouched;
    PhaseStopwatch off(untouched, false);
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
    off.lap(Phase::broad);
    EXPECT_EQ(untouched[Phase::broad], 0.0);
}

}  // namespace
}  // namespace trackphys
