#include "geometry/writeup_root_finders.hpp"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace trackphys::detail {
namespace {

double start_point(const glm::dvec3& r, const glm::dvec3& p) {
    double t0 = -r.z * r.z;
    for (int i = 0; i < 3; ++i) t0 = std::max(t0, r[i] * std::abs(p[i]) - r[i] * r[i]);
    return t0;
}

double f(const glm::dvec3& r, const glm::dvec3& p, double t) {
    double sum = -1.0;
    for (int i = 0; i < 3; ++i) {
        const double v = r[i] * p[i] / (r[i] * r[i] + t);
        sum += v * v;
    }
    return sum;
}

}  // namespace

LargestRoot writeup_bisection_largest_root(const glm::dvec3& r, const glm::dvec3& p) {
    double lo = start_point(r, p);
    double hi = std::max(lo, r.x * glm::length(p));
    const double width = kWriteupTolerance * r.z;
    int iterations = 0;
    while (hi - lo > width && iterations < 200) {
        const double mid = 0.5 * (lo + hi);
        (f(r, p, mid) > 0.0 ? lo : hi) = mid;
        ++iterations;
    }
    return {0.5 * (lo + hi), iterations};
}

LargestRoot writeup_newton_largest_root(const glm::dvec3& r, const glm::dvec3& p, int steps) {
    double t = start_point(r, p);
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

PointEllipsoid writeup_closest_point(const glm::dvec3& r, const glm::dvec3& p,
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
