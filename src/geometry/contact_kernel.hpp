#pragma once

// The ellipsoid-triangle contact in the ellipsoid's sorted frame (internal; the public
// entry is contact.hpp). Exposed for the tests and the benchmark, which check which
// path answered.

#include <array>

#include <glm/vec3.hpp>

namespace trackphys::detail {

/// How the answer was established.
enum class ContactPath {
    face_certified,    ///< the face candidate with its certificate (the shallow exit)
    edge_certified,    ///< an edge's closest-point candidate with its certificate
    vertex_certified,  ///< a vertex's closest point with its certificate
    enumerated,        ///< no certificate (deep): minimum over every local minimum
};

struct LocalContact {
    double depth;      ///< sigma (m)
    glm::dvec3 u;      ///< unit push direction, sorted frame
    glm::dvec3 point;  ///< contact point (Contact::point) relative to the center, sorted frame
    ContactPath path;
    int iterations;  ///< Newton steps over every root found
};

/// The triangle in the sorted frame: q[i] its vertices, edge[i] = q[i+1] - q[i], and
/// extent = the sum of |q[i][j]| over all coordinates (the size of its rounding errors).
struct LocalTriangle {
    std::array<glm::dvec3, 3> q;
    std::array<glm::dvec3, 3> edge;
    double extent;
};

/// sigma and its direction for radii x >= y >= z > 0; all inputs finite, z >= 2^-200 x,
/// and either every length within 2^-100..2^100 m or at the unit scale x in [1, 2) with
/// extent <= 2^206 x (the kernel's sixth powers of lengths must stay normal numbers). The
/// public entry scales every other configuration to unit scale by powers of two.
LocalContact contact_in_sorted_frame(const glm::dvec3& radii, const LocalTriangle& triangle);

}  // namespace trackphys::detail
