#pragma once

#include <vector>

#include "track/bezier_loop.hpp"
#include "trackphys/track/track_params.hpp"

namespace trackphys::track_detail {

/// What the road does along the centreline, sampled on a uniform arc-length grid: the bank
/// angle and where the rows of vertices go.
///
/// Banking follows the top-view curvature smoothed over about +-40 m (a triangle window),
/// so the road twists in gradually instead of jumping where Catmull-Rom's curvature does
/// (it is only continuous, not smooth, at the control points):
///     bank = max_bank * clamp(kappa_smooth * full_bank_radius, -1, 1).
/// Rows are spaced for a target edge length on the outer road edge,
///     edge(kappa) = clamp(edge_tight * sqrt(1 / (|kappa| tight_radius)),
///                         edge_tight, edge_straight)
/// (a constant chord error: the sagitta edge^2 / 8R is the same for every radius), and a row
/// step ds on the centreline stretches to ds (1 + |kappa| w / 2) on the outer edge, so the
/// row density is rho(s) = (1 + |kappa| w/2) / edge(kappa) rows per metre with kappa the
/// larger of the raw and smoothed curvature. Rows sit where the integral of rho reaches
/// whole multiples of its total / row count, which closes the loop with no odd last row.
struct RoadProfile {
    double grid_spacing = 0.0;         ///< arc length between grid points (m)
    std::vector<double> bank;          ///< bank (rad) at grid point k (distance k * spacing)
    std::vector<double> row_distance;  ///< distance of each row, increasing, first 0, < length

    /// Bank at distance s (linear between grid points, periodic).
    double bank_at(double s) const;
};

/// Builds the profile of loop for params.
RoadProfile make_road_profile(const BezierLoop& loop, const TrackParams& params);

}  // namespace trackphys::track_detail
