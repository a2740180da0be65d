#pragma once

#include <array>

#include <glm/vec2.hpp>

#include "trackphys/export.hpp"
#include "trackphys/math/types.hpp"

namespace trackphys {

/// A critical point of the distance from a point p to an ellipse x^2/rx^2 + y^2/ry^2 = 1:
/// p = point + offset * normal. The 2-D counterpart of EllipsoidCriticalPoint, used for the
/// edges of the ellipsoid-triangle contact (the ellipsoid's shadow on the plane orthogonal
/// to an edge is an ellipse).
struct EllipseCriticalPoint {
    glm::dvec2 point;   ///< point on the ellipse (m)
    glm::dvec2 normal;  ///< outward unit normal at point
    double offset;      ///< normal . (p - point) (m), > 0 outside along the normal
    /// u = -normal is a local minimum of u . p + ||D u|| over unit u (D = diag(radii)): an
    /// edge candidate of the contact kernel
    bool local_min;
};

/// Up to 4 critical points: the real roots of f(t) = sum (r_i p_i / (r_i^2 + t))^2 - 1, plus
/// the closed-form pair where a coordinate of p is exactly 0.
struct EllipseCriticalPoints {
    std::array<EllipseCriticalPoint, 4> points;
    int count;       ///< entries used in points
    int iterations;  ///< Newton steps over all roots
};

/// Every critical point of the distance from p to the ellipse with sorted_radii x >= y > 0
/// (m) centred at the origin along the axes. Throws trackphys::Error for radii not so or a
/// point not finite.
TRACKPHYS_API EllipseCriticalPoints ellipse_critical_points(const glm::dvec2& sorted_radii,
                                                            const glm::dvec2& p);

/// The closest point of that ellipse to p (count 1): its offset is the signed distance.
/// Throws as ellipse_critical_points does.
TRACKPHYS_API EllipseCriticalPoint closest_point_on_ellipse(const glm::dvec2& sorted_radii,
                                                            const glm::dvec2& p);

}  // namespace trackphys
