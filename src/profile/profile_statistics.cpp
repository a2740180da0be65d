#include "trackphys/profile/profile_statistics.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace trackphys {

Summary summarize(std::vector<double> values) {
    if (values.empty()) return {};
    std::sort(values.begin(), values.end());
    const auto rank = [&](double p) {
        // Nearest rank: the smallest value with at least p of the data at or below it.
        const double index = std::ceil(p * static_cast<double>(values.size())) - 1.0;
        return values[static_cast<std::size_t>(std::clamp(index, 0.0, double(values.size() - 1)))];
    };
    const double sum = std::accumulate(values.begin(), values.end(), 0.0);
    return {sum / static_cast<double>(values.size()), rank(0.50), rank(0.99), values.back()};
}

void ProfileStatistics::add(const UpdateProfile& profile) {
    update_us_.push_back(profile.update_us);
    for (std::size_t p = 0; p < phase_count; ++p) phase_us_[p].push_back(profile.phase_us[p]);
    candidates_ += static_cast<double>(profile.candidates);
    culled_tests_ += static_cast<double>(profile.culled_tests);
    exact_tests_ += static_cast<double>(profile.exact_tests);
    contacts_ += static_cast<double>(profile.contacts);
    ellipsoid_substeps_ += static_cast<double>(profile.ellipsoid_substeps);
    mid_queries_ += static_cast<double>(profile.mid_queries);
}

namespace {
double ratio(double a, double b) { return b > 0.0 ? a / b : 0.0; }
}  // namespace

double ProfileStatistics::mean_candidates() const { return ratio(candidates_, double(updates())); }
double ProfileStatistics::mean_exact_tests() const {
    return ratio(exact_tests_, double(updates()));
}
double ProfileStatistics::mean_contacts() const { return ratio(contacts_, double(updates())); }
double ProfileStatistics::mean_mid_queries() const {
    return ratio(mid_queries_, double(updates()));
}
double ProfileStatistics::mean_tested_per_ellipsoid_substep() const {
    return ratio(culled_tests_, ellipsoid_substeps_);
}

}  // namespace trackphys
