#include "track/bezier_loop.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include <glm/geometric.hpp>

#include "trackphys/assert.hpp"

namespace trackphys::track_detail {
namespace {

// 8-point Gauss-Legendre on [-1, 1]: nodes +-x_k with weights w_k (exact for degree 15).
constexpr double kGaussX[4] = {0.1834346424956498, 0.5255324099163290, 0.7966664774136267,
                               0.9602898564975363};
constexpr double kGaussW[4] = {0.3626837833783620, 0.3137066458778873, 0.2223810344533745,
                               0.1012285362903763};

}  // namespace

BezierLoop::BezierLoop(std::vector<glm::dvec3> points) : points_(std::move(points)) {
    const std::size_t n = points_.size();
    TP_ASSERT(n >= 3, "a Bezier loop needs at least 3 points");
    tangents_.resize(n);
    for (std::size_t i = 0; i < n; ++i)
        tangents_[i] = 0.5 * (points_[(i + 1) % n] - points_[(i + n - 1) % n]);

    cumulative_.resize(n * kSubintervals + 1);
    cumulative_[0] = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
        for (int k = 0; k < kSubintervals; ++k) {
            const double a = static_cast<double>(k) / kSubintervals;
            const double b = static_cast<double>(k + 1) / kSubintervals;
            const std::size_t index = i * kSubintervals + static_cast<std::size_t>(k);
            cumulative_[index + 1] = cumulative_[index] + arc_length(i, a, b);
        }
    }
}

// Bernstein form with c0 = P_i, c1 = P_i + T_i/3, c2 = P_{i+1} - T_{i+1}/3, c3 = P_{i+1}.
glm::dvec3 BezierLoop::segment_position(std::size_t i, double t) const {
    const std::size_t j = (i + 1) % points_.size();
    const glm::dvec3 c0 = points_[i];
    const glm::dvec3 c1 = points_[i] + tangents_[i] / 3.0;
    const glm::dvec3 c2 = points_[j] - tangents_[j] / 3.0;
    const glm::dvec3 c3 = points_[j];
    const double u = 1.0 - t;
    return (u * u * u) * c0 + (3.0 * u * u * t) * c1 + (3.0 * u * t * t) * c2 + (t * t * t) * c3;
}

// B'(t) = 3[(1-t)^2 (c1-c0) + 2(1-t)t (c2-c1) + t^2 (c3-c2)]; at t = 0 it is T_i, at 1 T_{i+1}.
glm::dvec3 BezierLoop::segment_derivative(std::size_t i, double t) const {
    const std::size_t j = (i + 1) % points_.size();
    const glm::dvec3 d0 = tangents_[i] / 3.0;
    const glm::dvec3 d1 = (points_[j] - tangents_[j] / 3.0) - (points_[i] + tangents_[i] / 3.0);
    const glm::dvec3 d2 = tangents_[j] / 3.0;
    const double u = 1.0 - t;
    return 3.0 * ((u * u) * d0 + (2.0 * u * t) * d1 + (t * t) * d2);
}

// B''(t) = 6[(1-t)(c2 - 2c1 + c0) + t(c3 - 2c2 + c1)].
glm::dvec3 BezierLoop::segment_second_derivative(std::size_t i, double t) const {
    const std::size_t j = (i + 1) % points_.size();
    const glm::dvec3 c0 = points_[i];
    const glm::dvec3 c1 = points_[i] + tangents_[i] / 3.0;
    const glm::dvec3 c2 = points_[j] - tangents_[j] / 3.0;
    const glm::dvec3 c3 = points_[j];
    return 6.0 * ((1.0 - t) * (c2 - 2.0 * c1 + c0) + t * (c3 - 2.0 * c2 + c1));
}

double BezierLoop::arc_length(std::size_t i, double a, double b) const {
    const double half = 0.5 * (b - a);
    const double mid = 0.5 * (a + b);
    double sum = 0.0;
    for (int k = 0; k < 4; ++k) {
        sum += kGaussW[k] * (glm::length(segment_derivative(i, mid - half * kGaussX[k])) +
                             glm::length(segment_derivative(i, mid + half * kGaussX[k])));
    }
    return half * sum;
}

void BezierLoop::locate(double s, std::size_t& segment, double& t) const {
    s = std::clamp(s, 0.0, length());
    // The subinterval holding s: the last cumulative entry <= s (never the final one).
    const auto upper = std::upper_bound(cumulative_.begin(), cumulative_.end() - 1, s);
    const std::size_t index = static_cast<std::size_t>(upper - cumulative_.begin()) - 1;
    segment = index / kSubintervals;
    const int k = static_cast<int>(index % kSubintervals);
    const double a = static_cast<double>(k) / kSubintervals;
    const double b = static_cast<double>(k + 1) / kSubintervals;
    const double target = s - cumulative_[index];  // arc length to cover inside [a, b]

    // Newton on f(t) = arc_length(a, t) - target, f' = |B'(t)| > 0, kept inside the
    // bracket [lo, hi] (f(lo) <= 0 <= f(hi)) and bisecting whenever a step leaves it. f is
    // increasing and smooth, so this converges quadratically from the linear guess.
    const double sub_length = cumulative_[index + 1] - cumulative_[index];
    double lo = a;
    double hi = b;
    t = sub_length > 0.0 ? a + (b - a) * std::clamp(target / sub_length, 0.0, 1.0) : a;
    for (int iteration = 0; iteration < 60; ++iteration) {
        const double f = arc_length(segment, a, t) - target;
        if (std::abs(f) <= 1e-13 * (1.0 + sub_length)) break;
        if (f < 0.0)
            lo = t;
        else
            hi = t;
        const double speed = glm::length(segment_derivative(segment, t));
        double next = speed > 0.0 ? t - f / speed : 0.5 * (lo + hi);
        if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
        if (next == t) break;
        t = next;
    }
}

BezierLoop::Point BezierLoop::at(double s) const {
    const double total = length();
    // s = total is the closing point; fold anything else into [0, total).
    if (s != total) {
        s = std::fmod(s, total);
        if (s < 0.0) s += total;
    }
    std::size_t segment = 0;
    double t = 0.0;
    locate(s, segment, t);

    Point point;
    point.position = s == total ? points_[0] : segment_position(segment, t);
    point.tangent = glm::normalize(segment_derivative(segment, t));
    point.horizontal_curvature = segment_horizontal_curvature(segment, t);
    return point;
}

double BezierLoop::segment_horizontal_curvature(std::size_t i, double t) const {
    // Top-view curvature of (x(t), z(t)) with left = +Y x tangent = (tz, 0, -tx):
    // kappa = (x'' z' - z'' x') / |(x', z')|^3 (infinite or NaN at a top-view cusp).
    const glm::dvec3 d1 = segment_derivative(i, t);
    const glm::dvec3 d2 = segment_second_derivative(i, t);
    const double speed = std::sqrt(d1.x * d1.x + d1.z * d1.z);
    return (d2.x * d1.z - d2.z * d1.x) / (speed * speed * speed);
}

}  // namespace trackphys::track_detail
