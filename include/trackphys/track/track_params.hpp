#pragma once

#include <cstdint>

#include "trackphys/export.hpp"

namespace trackphys {

/// The demo track's seed: what `trackphys drive`, `race`, `bake` and `track` generate when
/// no seed is given, and a Scenario's default.
inline constexpr std::uint64_t kDemoTrackSeed = 7;

/// Everything that shapes a generated track. The defaults, with seed = kDemoTrackSeed, give
/// the demo track (the default seed itself gives another track of the same kind): a closed
/// loop of 5 km, 14 m wide, banked up to 35 degrees, with 1 m walls, road edges of 0.5 m
/// in the tight turns and 10 strips across (about 300k triangles in 50 collider chunks of
/// ~100 m), so that a car's box swept for 1000 km/h over a 10 ms update meets a couple of
/// hundred road triangles in the tightest banked turn. Same parameters (seed included) ->
/// the same track, bit for bit.
struct TrackParams {
    /// Seeds the control-point generator (std::mt19937_64).
    std::uint64_t seed = 1;
    /// Target centreline length (m). The loop is scaled to it; the result is within 1e-6
    /// relative of this value.
    double length_m = 5000.0;
    /// Road width between the wall bases (m).
    double width_m = 14.0;
    /// Largest bank angle (degrees), reached in turns of full_bank_radius_m or tighter.
    double max_bank_deg = 35.0;
    /// Turn radius (m) at and below which the road gets the full bank; wider turns get a
    /// bank proportional to their curvature.
    double full_bank_radius_m = 150.0;
    /// Control-point heights are drawn in [-a, a] (m); 0 gives a flat track. a is capped
    /// at 4% of the control-point spacing (~300 m, at least 12 points per loop), which keeps
    /// grades below ~12% on short tracks.
    double elevation_amplitude_m = 10.0;
    /// Wall height above the road edge (m).
    double wall_height_m = 1.0;
    /// Wall thickness (m); each wall is a closed box profile (inner face, top, outer face).
    double wall_thickness_m = 0.5;
    /// No centreline turn is tighter than this radius (m); shapes that break it are
    /// regenerated. Must exceed half the width plus the wall thickness, or the inner edge
    /// of a turn would fold over itself.
    double min_turn_radius_m = 25.0;
    /// Length of the road's along-track edges (measured on the outer road edge, m) in turns
    /// of tight_radius_m and tighter.
    double edge_tight_m = 0.5;
    /// Length of the along-track edges on straights (m): the coarsest spacing.
    double edge_straight_m = 0.55;
    /// Turn radius (m) that gets edge_tight_m. In between, the edge length follows a
    /// constant chord error: edge = edge_tight_m * sqrt(radius / tight_radius_m), capped
    /// at edge_straight_m.
    double tight_radius_m = 60.0;
    /// Number of road strips across the width (so strips + 1 vertices per road row).
    int strips = 10;
    /// Target length of one collider chunk along the centreline (m).
    double chunk_length_m = 100.0;
};

/// Throws trackphys::Error naming the first field that is out of range and why (also
/// combinations: a minimum turn radius the width would fold, a length too short for the
/// turn radius, a density that would exceed the triangle budget). Returns normally when the
/// parameters can make a track.
TRACKPHYS_API void validate_track_params(const TrackParams& params);

}  // namespace trackphys
