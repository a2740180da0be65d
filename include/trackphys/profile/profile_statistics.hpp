#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include "trackphys/export.hpp"
#include "trackphys/profile/update_profile.hpp"

namespace trackphys {

/// Mean and order statistics of a series (same unit as the series).
struct Summary {
    double mean = 0.0;
    double p50 = 0.0;
    double p99 = 0.0;
    double max = 0.0;
};

/// Summary of values; p50 and p99 are nearest-rank percentiles. All zero when empty.
TRACKPHYS_API Summary summarize(std::vector<double> values);

/// Collects UpdateProfiles over a run and summarises them: per-update time, per-phase
/// time, and the mean counts per update.
class TRACKPHYS_API ProfileStatistics {
  public:
    /// Adds one update's profile.
    void add(const UpdateProfile& profile);

    std::size_t updates() const { return update_us_.size(); }
    Summary update_us() const { return summarize(update_us_); }
    Summary phase_us(Phase phase) const {
        return summarize(phase_us_[static_cast<std::size_t>(phase)]);
    }

    /// UpdateProfile's candidates, exact_tests and contacts, each a mean per update.
    double mean_candidates() const;
    double mean_exact_tests() const;
    double mean_contacts() const;
    /// Mid-phase queries per update (the other steps' ellipsoids reused a list).
    double mean_mid_queries() const;
    /// Sphere culls per ellipsoid per sub-step, averaged over the run.
    double mean_tested_per_ellipsoid_substep() const;

  private:
    std::vector<double> update_us_;
    std::array<std::vector<double>, phase_count> phase_us_;
    double candidates_ = 0.0, culled_tests_ = 0.0, exact_tests_ = 0.0, contacts_ = 0.0,
           ellipsoid_substeps_ = 0.0, mid_queries_ = 0.0;
};

}  // namespace trackphys
