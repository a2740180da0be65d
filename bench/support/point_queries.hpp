#pragma once

// The point-ellipsoid queries of the root-finder comparison (shared by bench_contact and
// trackphys-bench): deterministic points from tests/support's generator (seed 4242),
// sorted-frame radii and a point each, and the root finders compared on them.

#include <cstddef>
#include <vector>

#include <glm/vec3.hpp>

#include "support/point_cases.hpp"
#include "trackphys/geometry/point_ellipsoid.hpp"

namespace trackphys::bench {

struct PointQuery {
    glm::dvec3 radii;  ///< sorted, x >= y >= z > 0 (m)
    glm::dvec3 p;      ///< the query point in the sorted frame (m)
};

/// `count` points of one class, or of the whole mix when kind == PointClass::count.
std::vector<PointQuery> point_queries(test::PointClass kind, std::size_t count = 4096);

/// The largest root of the write-up's f(t): ours (the library's), or one of the write-up's
/// two solvers (src/geometry/writeup_root_finders.hpp).
enum class RootFinder { ours, bisection, writeup_newton };

/// The closest surface point of q's ellipsoid by `finder`.
PointEllipsoid closest_point(const PointQuery& q, RootFinder finder);

}  // namespace trackphys::bench
