#pragma once

#include <glm/vec3.hpp>

#include "trackphys/export.hpp"
#include "trackphys/geometry/ellipsoid.hpp"
#include "trackphys/geometry/triangle.hpp"
#include "trackphys/math/types.hpp"

namespace trackphys {

/// The exact contact between a solid ellipsoid and a triangle
/// (docs/design.md#exact-ellipsoid-triangle-contact).
struct Contact {
    /// Signed penetration (m): > 0 they overlap and depth is the minimum translation
    /// distance; < 0 they are apart by -depth. -infinity for a triangle with a non-finite
    /// coordinate (out of reach); otherwise finite: a separation beyond double's range
    /// (possible only with coordinates near +-1e308) saturates at -DBL_MAX.
    double depth;
    /// Unit world direction in which to move the ellipsoid to separate (when apart: away
    /// from the triangle).
    glm::dvec3 normal;
    /// Midpoint between the ellipsoid's extreme point towards the triangle and the
    /// triangle's touching point (m, world; a coordinate beyond double's range saturates at
    /// +-DBL_MAX).
    glm::dvec3 point;
};

/// sigma = min over unit u of max_i (u . q_i) + ||D u|| in the ellipsoid's frame, found
/// among the face, edge and vertex candidates (every local minimum of each), with exact
/// early exits for shallow contacts. Depth within 1e-9 m of the truth for every input
/// (measured ~1e-15 m typical, 1e-10 m for kilometre-sized triangles); normal within 1e-6
/// rad and point within 1e-6 m wherever the minimiser is unique. Degenerate triangles
/// (collinear or coincident vertices) act as the segment or point they are. Never NaN.
TRACKPHYS_API Contact ellipsoid_triangle_contact(const Ellipsoid& ellipsoid,
                                                 const Triangle& triangle);

}  // namespace trackphys
