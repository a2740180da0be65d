#include "track/track_shape.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <sstream>
#include <utility>

#include <glm/geometric.hpp>

#include "trackphys/error.hpp"

namespace trackphys::track_detail {
namespace {

// Spacing of the points that check a shape (m). Curvature peaks of a cubic are smooth and
// hundreds of metres wide at this scale, so 0.5 m resolves them; the clearance test uses
// every fourth point (2 m), whose error (< 1 m) the gap between roads absorbs.
constexpr double kCheckSpacing = 0.5;
constexpr int kClearanceStride = 4;

// Control points are about this far apart along the loop (m): a few corners per km.
constexpr double kControlSpacing = 300.0;

struct CheckPoint {
    glm::dvec3 position;
    double curvature;
    double distance;  // chord-sum distance from the start (m)
    std::size_t segment;
    double t;     // parameter in the segment
    double step;  // parameter step between this segment's points
};

std::vector<CheckPoint> sample_for_check(const BezierLoop& loop) {
    std::vector<CheckPoint> out;
    double distance = 0.0;
    glm::dvec3 previous = loop.points()[0];
    for (std::size_t i = 0; i < loop.segment_count(); ++i) {
        // A segment's arc is longer than its chord but, for these gentle cubics, well
        // under twice as long: twice the chord's worth of points keeps the spacing at or
        // below kCheckSpacing.
        const double chord =
            glm::distance(loop.points()[i], loop.points()[(i + 1) % loop.segment_count()]);
        const int steps = std::max(8, static_cast<int>(std::ceil(2.0 * chord / kCheckSpacing)));
        for (int k = 0; k < steps; ++k) {
            const double t = static_cast<double>(k) / steps;
            const glm::dvec3 p = loop.segment_position(i, t);
            distance += glm::distance(previous, p);
            previous = p;
            out.push_back(
                {p, loop.segment_horizontal_curvature(i, t), distance, i, t, 1.0 / steps});
        }
    }
    return out;
}

// |curvature| of the loop at its largest: the largest sampled value, with every local peak
// of the samples refined by golden-section search on its segment (the true peak lies
// within one parameter step of the sampled one; on short segments 0.5 m of sampling can
// miss it by a percent). A cusp gives infinity (or NaN, reported as infinity).
double max_abs_curvature(const BezierLoop& loop, const std::vector<CheckPoint>& samples) {
    constexpr double infinity = std::numeric_limits<double>::infinity();
    const auto magnitude = [&loop](std::size_t segment, double t) {
        const double k = std::abs(loop.segment_horizontal_curvature(segment, t));
        return std::isnan(k) ? infinity : k;
    };
    const std::size_t n = samples.size();
    double largest = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
        const CheckPoint& s = samples[i];
        const double here = std::isnan(s.curvature) ? infinity : std::abs(s.curvature);
        largest = std::max(largest, here);
        if (here < std::abs(samples[(i + n - 1) % n].curvature) ||
            here < std::abs(samples[(i + 1) % n].curvature) || here == infinity)
            continue;
        constexpr double golden = 0.6180339887498949;
        double lo = std::max(0.0, s.t - s.step), hi = std::min(1.0, s.t + s.step);
        double a = hi - golden * (hi - lo), b = lo + golden * (hi - lo);
        double fa = magnitude(s.segment, a), fb = magnitude(s.segment, b);
        for (int iteration = 0; iteration < 60 && hi - lo > 1e-12; ++iteration) {
            if (fa < fb) {
                lo = a;
                a = b;
                fa = fb;
                b = lo + golden * (hi - lo);
                fb = magnitude(s.segment, b);
            } else {
                hi = b;
                b = a;
                fb = fa;
                a = hi - golden * (hi - lo);
                fa = magnitude(s.segment, a);
            }
        }
        largest = std::max({largest, fa, fb});
    }
    return largest;
}

}  // namespace

double required_clearance(const TrackParams& params) {
    // Two road-plus-wall bands, and half a road width of open ground between them.
    return 1.5 * params.width_m + 2.0 * params.wall_thickness_m;
}

double elevation_amplitude(const TrackParams& params) {
    // Neighbouring control points differ in height by up to 2a over one spacing; 4% of
    // the spacing keeps grades near 8% (Catmull-Rom adds up to half again), and keeps the
    // horizontal shape from shrinking much when the loop is scaled to its 3-D length.
    return std::min(params.elevation_amplitude_m,
                    0.04 * params.length_m / control_point_count(params));
}

int control_point_count(const TrackParams& params) {
    return std::clamp(static_cast<int>(std::lround(params.length_m / kControlSpacing)), 12, 64);
}

std::vector<glm::dvec3> draw_control_points(const TrackParams& params, double relax,
                                            std::mt19937_64& rng) {
    const int count = control_point_count(params);
    const double radius = params.length_m / (2.0 * std::numbers::pi);
    const double amplitude = elevation_amplitude(params);
    // Our own uniform map (not std::uniform_real_distribution, whose algorithm is
    // implementation-defined) keeps the track identical across standard libraries.
    const auto uniform = [&rng](double lo, double hi) {
        const double unit = static_cast<double>(rng() >> 11) * 0x1.0p-53;
        return lo + (hi - lo) * unit;
    };
    std::vector<glm::dvec3> points;
    points.reserve(static_cast<std::size_t>(count));
    for (int i = 0; i < count; ++i) {
        const double angle = 2.0 * std::numbers::pi * (i + relax * uniform(-0.3, 0.3)) / count;
        const double r = radius * (1.0 + relax * uniform(-0.45, 0.45));
        const double height = amplitude * uniform(-1.0, 1.0);
        points.emplace_back(r * std::cos(angle), height, r * std::sin(angle));
    }
    return points;
}

BezierLoop scale_to_length(std::vector<glm::dvec3> points, double length_m) {
    // The length is linear in a horizontal scale except for the heights' share, which is a
    // few 1e-3 on sane grades: each round gains that factor, so a handful of rounds reach
    // 1e-9. The cap only guards against pathological shapes.
    for (int round = 0; round < 20; ++round) {
        const BezierLoop loop(points);
        const double ratio = length_m / loop.length();
        if (std::abs(ratio - 1.0) <= 1e-9) return loop;
        for (glm::dvec3& p : points) {
            p.x *= ratio;
            p.z *= ratio;
        }
    }
    return BezierLoop(std::move(points));
}

std::string shape_problem(const BezierLoop& loop, const TrackParams& params) {
    const std::vector<CheckPoint> samples = sample_for_check(loop);
    std::ostringstream why;

    const double max_curvature = max_abs_curvature(loop, samples);
    if (!(max_curvature * params.min_turn_radius_m <= 1.0)) {
        why << "turn of radius " << 1.0 / max_curvature << " m is tighter than min_turn_radius_m "
            << params.min_turn_radius_m;
        return why.str();
    }

    // Two points of one smooth curve whose curvature stays below 1/R are at least the chord
    // of an R-circle apart for arc distances d <= pi R (Schur's comparison theorem):
    // |p(s) - p(s + d)| >= 2 R sin(d / 2R). Validation makes 2R >= clearance, so beyond
    // d_local = 2R asin(clearance / 2R) closeness is never the curve's own bend: any pair
    // that far apart along the track and closer than the clearance is another part of the
    // road coming back.
    const double clearance = required_clearance(params);
    const double r = params.min_turn_radius_m;
    const double d_local = 2.0 * r * std::asin(std::min(1.0, clearance / (2.0 * r)));
    const double total =
        samples.back().distance + glm::distance(samples.back().position, samples.front().position);

    // Bucket the check points on a horizontal grid with cells of one clearance, so each
    // point only meets the 3 x 3 cells around it. Sorting by cell (then index) keeps the
    // scan order independent of any hashing.
    std::vector<std::pair<std::pair<std::int64_t, std::int64_t>, std::size_t>> cells;
    for (std::size_t i = 0; i < samples.size(); i += kClearanceStride) {
        const glm::dvec3& p = samples[i].position;
        cells.push_back({{static_cast<std::int64_t>(std::floor(p.x / clearance)),
                          static_cast<std::int64_t>(std::floor(p.z / clearance))},
                         i});
    }
    std::sort(cells.begin(), cells.end());
    for (const auto& [cell, i] : cells) {
        for (std::int64_t dx = -1; dx <= 1; ++dx) {
            for (std::int64_t dz = -1; dz <= 1; ++dz) {
                const std::pair<std::int64_t, std::int64_t> key{cell.first + dx, cell.second + dz};
                auto it = std::lower_bound(cells.begin(), cells.end(),
                                           std::make_pair(key, std::size_t{0}));
                for (; it != cells.end() && it->first == key; ++it) {
                    const std::size_t j = it->second;
                    if (j <= i) continue;
                    const double along = samples[j].distance - samples[i].distance;
                    if (std::min(along, total - along) <= d_local) continue;
                    const glm::dvec3 gap = samples[j].position - samples[i].position;
                    const double horizontal = std::sqrt(gap.x * gap.x + gap.z * gap.z);
                    if (horizontal < clearance) {
                        why << "the road comes within " << horizontal << " m of itself (at "
                            << samples[i].distance << " m and " << samples[j].distance
                            << " m along; needs " << clearance << " m)";
                        return why.str();
                    }
                }
            }
        }
    }
    return {};
}

TrackShape make_track_shape(const TrackParams& params) {
    std::mt19937_64 rng(params.seed);
    std::string last_problem;
    for (int attempt = 0; attempt < kMaxShapeAttempts; ++attempt) {
        // Full jitter first, a plain circle on the last attempt.
        const double relax = 1.0 - static_cast<double>(attempt) / (kMaxShapeAttempts - 1);
        BezierLoop loop = scale_to_length(draw_control_points(params, relax, rng), params.length_m);
        last_problem = shape_problem(loop, params);
        if (last_problem.empty()) return {std::move(loop), attempt};
    }
    throw Error("track generation: no valid shape for seed " + std::to_string(params.seed) +
                " after " + std::to_string(kMaxShapeAttempts) + " attempts; last: " + last_problem);
}

}  // namespace trackphys::track_detail
