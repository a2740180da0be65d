#include "point_queries.hpp"

#include "geometry/writeup_root_finders.hpp"

namespace trackphys::bench {

std::vector<PointQuery> point_queries(test::PointClass kind, std::size_t count) {
    test::PointCaseGenerator<3> generator(4242);
    std::vector<PointQuery> queries;
    while (queries.size() < count) {
        const test::PointCase<3> c = generator.next();
        if (kind != test::PointClass::count && c.kind != kind) continue;
        queries.push_back({{c.radii[0], c.radii[1], c.radii[2]}, {c.p[0], c.p[1], c.p[2]}});
    }
    return queries;
}

PointEllipsoid closest_point(const PointQuery& q, RootFinder finder) {
    switch (finder) {
        case RootFinder::bisection:
            return detail::writeup_closest_point(q.radii, q.p,
                                                 detail::WriteupRootFinder::bisection);
        case RootFinder::writeup_newton:
            return detail::writeup_closest_point(q.radii, q.p, detail::WriteupRootFinder::newton);
        case RootFinder::ours:
            break;
    }
    return closest_point_on_sorted_ellipsoid(q.radii, q.p);
}

}  // namespace trackphys::bench
