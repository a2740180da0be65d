#pragma once

// The ellipsoid-ellipsoid contact's contract against the long-double reference, shared by
// the cold call's tests and the warm-started call's: depth within 1e-9 m (1e-11 relative
// beyond 100 m) everywhere, normal within 1e-6 rad and point within 1e-6 m where the
// minimiser is unique, a unit normal and nothing NaN. Tests only.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "support/ellipsoid_pair_cases.hpp"
#include "support/ellipsoid_pair_reference.hpp"
#include "trackphys/geometry/contact.hpp"

namespace trackphys::test {

inline bool finite(const Contact& c) {
    return !std::isnan(c.depth) && std::isfinite(c.normal.x) && std::isfinite(c.normal.y) &&
           std::isfinite(c.normal.z) && std::isfinite(c.point.x) && std::isfinite(c.point.y) &&
           std::isfinite(c.point.z);
}

inline std::string describe_one(const Ellipsoid& e) {
    char buffer[512];
    std::snprintf(buffer, sizeof buffer,
                  "{c (%.17g %.17g %.17g) q (%.17g %.17g %.17g %.17g) axes (%.17g %.17g %.17g)}",
                  e.center().x, e.center().y, e.center().z, e.orientation().w, e.orientation().x,
                  e.orientation().y, e.orientation().z, e.semi_axes().x, e.semi_axes().y,
                  e.semi_axes().z);
    return buffer;
}

inline std::string describe(const Ellipsoid& a, const Ellipsoid& b) {
    return "a " + describe_one(a) + " b " + describe_one(b);
}

inline std::string describe(const PairCase& c) {
    return std::string(pair_kind_name(c.kind)) + ": " + describe(c.a, c.b);
}

inline double largest_axis(const Ellipsoid& a, const Ellipsoid& b) {
    return std::max(a.sorted_radii().x, b.sorted_radii().x);
}

/// The contract's depth tolerance: 1e-9 m, or 1e-11 relative beyond 100 m.
inline double depth_tolerance(double magnitude) { return std::max(1e-9, 1e-11 * magnitude); }

inline double angle(const glm::dvec3& u, const glm::dvec3& v) {
    return std::atan2(glm::length(glm::cross(u, v)), glm::dot(u, v));
}

/// The largest errors seen over a family, and how many of its pairs had a unique minimiser.
struct KindStats {
    long cases = 0, unique = 0;
    double depth_error = 0, angle_error = 0, point_error = 0;
};

/// Checks `got`, a contact of c's pair, against the pair's reference (fatal failures; the
/// caller checks HasFatalFailure). `what` names the call in the failure messages.
inline void check_contract(const PairCase& c, const Contact& got, const PairReferenceResult& ref,
                           KindStats& stats, const std::string& what = "") {
    const std::string context = describe(c) + what;
    ASSERT_TRUE(finite(got)) << context;
    ASSERT_NEAR(glm::length(got.normal), 1.0, 1e-12) << context;
    const double scale = largest_axis(c.a, c.b);
    // The reference is a true minimum: no sampled direction is lower.
    ASSERT_GE(double(ref.sampled_min - ref.depth), -1e-13 * scale) << context;
    const double magnitude = std::max(std::abs(double(ref.depth)), scale);
    const double depth_error = std::abs(got.depth - double(ref.depth));
    ASSERT_LE(depth_error, depth_tolerance(magnitude))
        << context << " got " << got.depth << " want " << double(ref.depth);
    ++stats.cases;
    stats.depth_error = std::max(stats.depth_error, depth_error);
    // Unique: the runner-up is 1e-6 of the scale worse and h curves up around the minimiser
    // (else no double computation fixes the direction to 1e-6 rad).
    if (ref.runner_up - ref.depth >= 1e-6 * scale && ref.rise >= 5e-11 * scale) {
        ++stats.unique;
        const glm::dvec3 want_normal(-double(ref.n.x), -double(ref.n.y), -double(ref.n.z));
        const glm::dvec3 want_point(double(ref.point.x), double(ref.point.y), double(ref.point.z));
        const double a = angle(got.normal, want_normal);
        const double point_error = glm::distance(got.point, want_point);
        ASSERT_LE(a, 1e-6) << context;
        ASSERT_LE(point_error, std::max(1e-6, 1e-11 * magnitude)) << context;
        stats.angle_error = std::max(stats.angle_error, a);
        stats.point_error = std::max(stats.point_error, point_error);
    }
}

}  // namespace trackphys::test
