#include "trackphys/collision/swept_ellipsoid.hpp"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace trackphys {

namespace {

/// The segment [a, b], set up once for the distances of both ends of the inner segment.
struct Segment {
    glm::dvec3 a, along;
    double length2;

    Segment(const glm::dvec3& start, const glm::dvec3& end)
        : a(start), along(end - start), length2(glm::dot(along, along)) {}

    /// Squared distance from p to the segment.
    double distance_squared(const glm::dvec3& p) const {
        const double t =
            length2 > 0.0 ? std::clamp(glm::dot(p - a, along) / length2, 0.0, 1.0) : 0.0;
        const glm::dvec3 gap = p - (a + t * along);
        return glm::dot(gap, gap);
    }
};

}  // namespace

Aabb SweptEllipsoid::bounds() const {
    // The scaled ellipsoid reaches (scale - 1) r_x beyond the ellipsoid along any axis.
    const Aabb start = ellipsoid.bounds().padded((scale() - 1.0) * ellipsoid.sorted_radii().x);
    const glm::dvec3 move = end - ellipsoid.center();
    Aabb box = start;
    box.expand(Aabb{start.min + move, start.max + move});
    return box;
}

// Write E (semi-axes D, sorted axes A) for the ellipsoid, f for the scale, c(t) for the
// center along the segment. A point of the inner shape is c1 + A1 D f1 s with |s| <= 1 and
// c1 on the inner segment; the point c0 + A0 D f1 s, with c0 the closest point of the outer
// segment to c1, lies in f1 E0 about c0, and the two differ by at most
// |c1 - c0| + ||A1 - A0|| f1 r_x (the Frobenius norm bounds the operator norm). The
// distance to a segment is convex, so the inner segment's ends bound |c1 - c0|. Finally f1 E
// grown by rho stays inside f0 E when rho <= (f0 - f1) r_z = margin0 - margin1, because
// f0 E = f1 E + (f0 - f1) E and E holds the ball of radius r_z.
bool SweptEllipsoid::contains(const SweptEllipsoid& inner) const {
    // The rounding of these few operations is far below a nanometre on any map.
    constexpr double kRounding = 1e-9;
    const glm::dvec3& radii = ellipsoid.sorted_radii();
    if (inner.ellipsoid.sorted_radii() != radii) return false;
    // What the turn leaves of the margin difference for the centre offset; cheapest first,
    // the offset compared in squares.
    double room = margin - inner.margin - kRounding;
    if (!(room >= 0.0)) return false;
    const glm::dmat3 turn = inner.ellipsoid.sorted_axes() - ellipsoid.sorted_axes();
    room -= std::sqrt(glm::dot(turn[0], turn[0]) + glm::dot(turn[1], turn[1]) +
                      glm::dot(turn[2], turn[2])) *
            inner.scale() * radii.x;
    if (!(room >= 0.0)) return false;
    const Segment segment(ellipsoid.center(), end);
    const double room_squared = room * room;
    return segment.distance_squared(inner.ellipsoid.center()) <= room_squared &&
           segment.distance_squared(inner.end) <= room_squared;
}

}  // namespace trackphys
