#pragma once

// The point-ellipsoid queries of the root-finder comparison (header-only, shared by
// bench_contact and `trackphys bench`): deterministic points from tests/support's generator
// (seed 4242), sorted-frame radii and a point each.

#include <cstddef>
#include <vector>

#include <glm/vec3.hpp>

#include "support/point_cases.hpp"

namespace trackphys::bench {

struct PointQuery {
    glm::dvec3 radii;  ///< sorted, x >= y >= z > 0 (m)
    glm::dvec3 p;      ///< the query point in the sorted frame (m)
};

/// `count` points of one class, or of the whole mix when kind == PointClass::count.
inline std::vector<PointQuery> point_queries(test::PointClass kind, std::size_t count = 4096) {
    test::PointCaseGenerator<3> generator(4242);
    std::vector<PointQuery> queries;
    while (queries.size() < count) {
        const test::PointCase<3> c = generator.next();
        if (kind != test::PointClass::count && c.kind != kind) continue;
        queries.push_back({{c.radii[0], c.radii[1], c.radii[2]}, {c.p[0], c.p[1], c.p[2]}});
    }
    return queries;
}

}  // namespace trackphys::bench
