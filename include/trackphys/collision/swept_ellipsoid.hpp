#pragma once

#include <glm/vec3.hpp>

#include "trackphys/export.hpp"
#include "trackphys/geometry/aabb.hpp"
#include "trackphys/geometry/ellipsoid.hpp"
#include "trackphys/math/types.hpp"

namespace trackphys {

/// The shape MidPhase::query_swept_ellipsoid and PlaneTree::query_swept_ellipsoid list
/// triangles for: the ellipsoid scaled about its center by 1 + margin / (smallest semi-axis)
/// (which holds it grown by `margin`, m), its center moving from ellipsoid.center() to `end`
/// with its orientation fixed.
///
/// A list queried for one shape holds every triangle of any shape it contains(), so a
/// caller can query once for a shape that looks ahead and reuse the list while later
/// shapes stay inside it (World does, per step).
struct TRACKPHYS_API SweptEllipsoid {
    Ellipsoid ellipsoid;
    glm::dvec3 end;
    double margin;  ///< m, >= 0

    /// The factor the query scales the ellipsoid by: 1 + margin / smallest semi-axis.
    double scale() const { return 1.0 + margin / ellipsoid.sorted_radii().z; }

    /// A box that holds the shape.
    Aabb bounds() const;

    /// True only if `inner` lies inside this shape: same semi-axes, and its every point
    /// within this shape (a sufficient test, exact to 1e-9 m; see the .cpp for the proof).
    bool contains(const SweptEllipsoid& inner) const;
};

}  // namespace trackphys
