#include "track/road_profile.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <numbers>

#include "trackphys/assert.hpp"

namespace trackphys::track_detail {
namespace {

// Grid spacing for the curvature, bank and density profiles (m).
constexpr double kGridSpacing = 0.5;
// Half-width of each of the two box filters that smooth the curvature for banking (m);
// together a triangle window of +-40 m, about the length of a tight hairpin.
constexpr double kBankSmoothingHalfWidth = 20.0;
// Half-width of the box filter over the bank itself (m): the bank saturates at its maximum
// in every turn tighter than full_bank_radius_m, so between two opposite turns it would
// swing from one side to the other within a few metres. Spreading each swing over 120 m
// keeps the road's twist gentle enough for a car's four wheels to stay on it.
constexpr double kBankTransitionHalfWidth = 60.0;

// Periodic moving average over 2 * half + 1 grid points.
std::vector<double> box_filter(const std::vector<double>& in, std::size_t half) {
    const std::size_t n = in.size();
    half = std::min(half, (n - 1) / 2);
    const double window = static_cast<double>(2 * half + 1);
    double sum = 0.0;
    for (std::size_t k = 0; k <= 2 * half; ++k) sum += in[(k + n - half) % n];
    std::vector<double> out(n);
    for (std::size_t k = 0; k < n; ++k) {
        out[k] = sum / window;
        sum += in[(k + half + 1) % n] - in[(k + n - half) % n];
    }
    return out;
}

}  // namespace

double RoadProfile::bank_at(double s) const {
    const double x = s / grid_spacing;
    const double base = std::floor(x);
    const double f = x - base;
    const std::size_t n = bank.size();
    const std::size_t k = static_cast<std::size_t>(base) % n;
    return (1.0 - f) * bank[k] + f * bank[(k + 1) % n];
}

RoadProfile make_road_profile(const BezierLoop& loop, const TrackParams& params) {
    const double length = loop.length();
    const std::size_t n =
        std::max<std::size_t>(16, static_cast<std::size_t>(std::ceil(length / kGridSpacing)));
    RoadProfile profile;
    profile.grid_spacing = length / static_cast<double>(n);

    std::vector<double> curvature(n);
    for (std::size_t k = 0; k < n; ++k)
        curvature[k] = loop.at(static_cast<double>(k) * profile.grid_spacing).horizontal_curvature;

    const auto half =
        static_cast<std::size_t>(std::lround(kBankSmoothingHalfWidth / profile.grid_spacing));
    const std::vector<double> smooth = box_filter(box_filter(curvature, half), half);

    const double max_bank = params.max_bank_deg * std::numbers::pi / 180.0;
    std::vector<double> saturated(n);
    for (std::size_t k = 0; k < n; ++k)
        saturated[k] = max_bank * std::clamp(smooth[k] * params.full_bank_radius_m, -1.0, 1.0);
    const auto transition =
        static_cast<std::size_t>(std::lround(kBankTransitionHalfWidth / profile.grid_spacing));
    profile.bank = box_filter(saturated, transition);

    // Row density (rows per metre) at each grid point, then its running integral
    // (trapezoids) over the closed loop.
    const auto density = [&](std::size_t k) {
        const double kappa = std::max(std::abs(curvature[k]), std::abs(smooth[k]));
        const double edge =
            kappa > 0.0 ? std::clamp(params.edge_tight_m / std::sqrt(kappa * params.tight_radius_m),
                                     params.edge_tight_m, params.edge_straight_m)
                        : params.edge_straight_m;
        return (1.0 + kappa * 0.5 * params.width_m) / edge;
    };
    std::vector<double> integral(n + 1, 0.0);
    for (std::size_t k = 0; k < n; ++k)
        integral[k + 1] =
            integral[k] + 0.5 * (density(k) + density((k + 1) % n)) * profile.grid_spacing;

    const double total = integral[n];
    const auto rows = static_cast<std::size_t>(std::ceil(total));
    TP_ASSERT(rows >= 3, "a track needs at least 3 rows");
    profile.row_distance.resize(rows);
    std::size_t k = 0;
    for (std::size_t r = 0; r < rows; ++r) {
        // Invert the piecewise-linear integral: the grid interval holding the target.
        const double target = total * static_cast<double>(r) / static_cast<double>(rows);
        while (k + 1 < n && integral[k + 1] <= target) ++k;
        const double step = integral[k + 1] - integral[k];
        const double f = step > 0.0 ? (target - integral[k]) / step : 0.0;
        profile.row_distance[r] = (static_cast<double>(k) + f) * profile.grid_spacing;
    }
    return profile;
}

}  // namespace trackphys::track_detail
