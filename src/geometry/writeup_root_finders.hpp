#pragma once

// The write-up's two solvers for the largest root of
//     f(t) = sum_i (r_i p_i / (r_i^2 + t))^2 - 1      (radii sorted, r_0 >= r_1 >= r_2)
// reconstructed from its text so that the benchmark and the tests can measure its claims
// (docs/design.md#root-finding). They work on t directly, with no guard for a
// zero coordinate and no offset from the pole: exactly what the measurement criticises.
// Not used by the library: header-only, for the benchmark and the tests only.

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "trackphys/geometry/point_ellipsoid.hpp"

namespace trackphys::detail {

struct LargestRoot {
    double t;
    int iterations;
};

/// The write-up's distance tolerance: 1e-5 m.
inline constexpr double kWriteupTolerance = 1e-5;

enum class WriteupRootFinder {
    bisection,  ///< the write-up's first solver: bisection on t to 1e-5 m
    newton,     ///< the write-up's Newton on f from its starting point, 5 steps
};

// The write-up's starting point and f, shared by its two finders.
namespace writeup {

inline double start_point(const glm::dvec3& r, const glm::dvec3& p) {
    double t0 = -r.z * r.z;
    for (int i = 0; i < 3; ++i) t0 = std::max(t0, r[i] * std::abs(p[i]) - r[i] * r[i]);
    return t0;
}

inline double f(const glm::dvec3& r, const glm::dvec3& p, double t) {
    double sum = -1.0;
    for (int i = 0; i < 3; ++i) {
        const double v = r[i] * p[i] / (r[i] * r[i] + t);
        sum += v * v;
    }
    return sum;
}

}  // namespace writeup

/// Bisection on t: the bracket [max(-r_2^2, max_i (r_i |p_i| - r_i^2)), r_0 |p|] (f >= 0
/// at its left end, f <= 0 at its right end) halved until its width is below 1e-5 m * r_2,
/// i.e. about 1e-5 m of distance where the closest point is not near the pole.
inline LargestRoot writeup_bisection_largest_root(const glm::dvec3& r, const glm::dvec3& p) {
    double lo = writeup::start_point(r, p);
    double hi = std::max(lo, r.x * glm::length(p));
    const double width = kWriteupTolerance * r.z;
    int iterations = 0;
    while (hi - lo > width && iterations < 200) {
        const double mid = 0.5 * (lo + hi);
        (writeup::f(r, p, mid) > 0.0 ? lo : hi) = mid;
        ++iterations;
    }
    return {0.5 * (lo + hi), iterations};
}

/// Newton on f from t0 = max(-r_2^2, max_i (r_i |p_i| - r_i^2)), where f >= 0 and f is
/// decreasing and convex, for a fixed number of steps (the write-up's 5).
inline LargestRoot writeup_newton_largest_root(const glm::dvec3& r, const glm::dvec3& p,
                                               int steps = 5) {
    double t = writeup::start_point(r, p);
    for (int k = 0; k < steps; ++k) {
        double value = -1.0;
        double slope = 0.0;
        for (int i = 0; i < 3; ++i) {
            const double w = r[i] * r[i] + t;
            const double v = r[i] * p[i] / w;
            value += v * v;
            slope -= 2.0 * v * v / w;
        }
        t -= value / slope;
    }
    return {t, steps};
}

/// closest_point_on_sorted_ellipsoid with one of the write-up's finders, the closest point
/// computed from t as the write-up does. They reproduce its failures: far off (bisection
/// near the smallest axis' plane) or NaN (Newton on a coordinate that is exactly 0).
inline PointEllipsoid writeup_closest_point(const glm::dvec3& r, const glm::dvec3& p,
                                            WriteupRootFinder finder) {
    const LargestRoot root = finder == WriteupRootFinder::bisection
                                 ? writeup_bisection_largest_root(r, p)
                                 : writeup_newton_largest_root(r, p);
    PointEllipsoid result{};
    glm::dvec3 n;
    for (int i = 0; i < 3; ++i) {
        const double w = r[i] * r[i] + root.t;
        result.point[i] = r[i] * r[i] * p[i] / w;
        n[i] = p[i] / w;
    }
    result.normal = glm::normalize(n);
    const double distance = glm::distance(p, result.point);
    result.distance = root.t < 0.0 ? -distance : distance;
    result.iterations = root.iterations;
    return result;
}

}  // namespace trackphys::detail
