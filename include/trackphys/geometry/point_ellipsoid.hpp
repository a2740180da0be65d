#pragma once

#include <array>

#include <glm/vec3.hpp>

#include "trackphys/export.hpp"
#include "trackphys/geometry/ellipsoid.hpp"
#include "trackphys/math/types.hpp"

namespace trackphys {

/// The surface point of an ellipsoid closest to a query point.
struct PointEllipsoid {
    glm::dvec3 point;   ///< closest surface point (m)
    glm::dvec3 normal;  ///< outward unit surface normal at point
    double distance;    ///< signed distance from the surface (m), negative inside
    int iterations;     ///< Newton steps spent, for benchmarks
};

/// Closest surface point of `ellipsoid` to the world point p, with the signed distance
/// (negative inside). Exact to ~1e-15 relative for every finite input; throws
/// trackphys::Error for a point that is not finite.
TRACKPHYS_API PointEllipsoid closest_point_on_ellipsoid(const Ellipsoid& ellipsoid,
                                                        const glm::dvec3& p);

/// The same in the sorted frame: radii x >= y >= z > 0 (m), p in that frame. Throws
/// trackphys::Error for radii not so (an ellipsoid's semi_axes() rather than its
/// sorted_radii(), say) or a point not finite.
TRACKPHYS_API PointEllipsoid closest_point_on_sorted_ellipsoid(const glm::dvec3& sorted_radii,
                                                               const glm::dvec3& p);

/// A critical point of the distance from a point p to the surface: p lies on the normal
/// line of point, p = point + offset * normal.
struct EllipsoidCriticalPoint {
    glm::dvec3 point;   ///< surface point (m, sorted frame)
    glm::dvec3 normal;  ///< outward unit normal at point
    double offset;      ///< normal . (p - point) (m): > 0 when p is outside along the normal
    /// u = -normal is a local minimum of u . p + ||D u|| over unit u (D = diag(radii)): a
    /// contact candidate of the vertex p (for p inside: a local minimum of |p - point|)
    bool local_min;
};

/// Every critical point of the distance from p to an ellipsoid surface: one per real root
/// of f(t) (up to 6), plus Eberly's closed-form points where a coordinate of p is exactly
/// 0 (a circle or sphere of them for equal radii is represented by its axis points).
struct EllipsoidCriticalPoints {
    std::array<EllipsoidCriticalPoint, 8> points;
    int count;       ///< entries used in points
    int iterations;  ///< Newton steps over all roots
};

/// All critical points of the distance from p (sorted frame) to the ellipsoid with
/// sorted_radii x >= y >= z > 0 (m). Roots are found by the robust concave-h climb beside
/// each pole, which also proves when a middle interval of f holds no root. Throws
/// trackphys::Error as closest_point_on_sorted_ellipsoid does.
TRACKPHYS_API EllipsoidCriticalPoints ellipsoid_critical_points(const glm::dvec3& sorted_radii,
                                                                const glm::dvec3& p);

}  // namespace trackphys
