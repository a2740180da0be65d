#pragma once

#include <random>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "track/bezier_loop.hpp"
#include "trackphys/track/track_params.hpp"

namespace trackphys::track_detail {

/// The centreline's shape: the accepted Bezier loop and how many shapes were rejected first.
struct TrackShape {
    BezierLoop loop;
    int rejected = 0;
};

/// Number of control points (= Bezier segments) for params: about one per 300 m, 12 to 64.
int control_point_count(const TrackParams& params);

/// Amplitude of the control-point heights (m): params.elevation_amplitude_m, capped at 4%
/// of the control-point spacing.
double elevation_amplitude(const TrackParams& params);

/// Draws control points around a circle of circumference params.length_m (angles and radii
/// jittered by `relax` in [0, 1], heights in +-elevation_amplitude(params)) from rng.
std::vector<glm::dvec3> draw_control_points(const TrackParams& params, double relax,
                                            std::mt19937_64& rng);

/// Scales the loop's horizontal coordinates (x, z) until its 3-D length is
/// params.length_m within 1e-9 relative (heights stay as drawn).
BezierLoop scale_to_length(std::vector<glm::dvec3> points, double length_m);

/// Why the loop is not a valid track for params (a turn tighter than min_turn_radius_m, or
/// two parts of the road closer than the walls allow); empty when it is valid.
std::string shape_problem(const BezierLoop& loop, const TrackParams& params);

/// Horizontal distance the centrelines of two different parts of the track must keep (m):
/// both roads with their walls, plus a gap.
double required_clearance(const TrackParams& params);

/// Draws shapes from params.seed until one is valid; each rejection relaxes the next draw
/// towards a circle, which is always valid for parameters that pass validation. Throws
/// trackphys::Error if kMaxShapeAttempts draws all fail.
TrackShape make_track_shape(const TrackParams& params);

constexpr int kMaxShapeAttempts = 64;

}  // namespace trackphys::track_detail
