#pragma once

// The write-up's two solvers for the largest root of
//     f(t) = sum_i (r_i p_i / (r_i^2 + t))^2 - 1      (radii sorted, r_0 >= r_1 >= r_2)
// reconstructed from its text so that the benchmark and the tests can measure its claims
// (docs/design.md#root-finding). They work on t directly, with no guard for a
// zero coordinate and no offset from the pole: exactly what the measurement criticises.
// Not used by the library: private, for the benchmark and the tests only.

#include <glm/vec3.hpp>

#include "trackphys/geometry/point_ellipsoid.hpp"

namespace trackphys::detail {

struct LargestRoot {
    double t;
    int iterations;
};

/// The write-up's distance tolerance: 1e-5 m.
inline constexpr double kWriteupTolerance = 1e-5;

/// Bisection on t: the bracket [max(-r_2^2, max_i (r_i |p_i| - r_i^2)), r_0 |p|] (f >= 0
/// at its left end, f <= 0 at its right end) halved until its width is below 1e-5 m * r_2,
/// i.e. about 1e-5 m of distance where the closest point is not near the pole.
LargestRoot writeup_bisection_largest_root(const glm::dvec3& sorted_radii, const glm::dvec3& p);

/// Newton on f from t0 = max(-r_2^2, max_i (r_i |p_i| - r_i^2)), where f >= 0 and f is
/// decreasing and convex, for a fixed number of steps (the write-up's 5).
LargestRoot writeup_newton_largest_root(const glm::dvec3& sorted_radii, const glm::dvec3& p,
                                        int steps = 5);

enum class WriteupRootFinder {
    bisection,  ///< the write-up's first solver: bisection on t to 1e-5 m
    newton,     ///< the write-up's Newton on f from its starting point, 5 steps
};

/// closest_point_on_sorted_ellipsoid with one of the write-up's finders, the closest point
/// computed from t as the write-up does. They reproduce its failures: far off (bisection
/// near the smallest axis' plane) or NaN (Newton on a coordinate that is exactly 0).
PointEllipsoid writeup_closest_point(const glm::dvec3& sorted_radii, const glm::dvec3& p,
                                     WriteupRootFinder finder);

}  // namespace trackphys::detail
