#pragma once

// The long-double contact reference (contact_reference.hpp) for a world configuration:
// the triangle taken into the ellipsoid's sorted frame in long double, the answer taken
// back to world coordinates. Tests only.

#include <array>

#include <glm/vec3.hpp>

#include "support/contact_reference.hpp"
#include "trackphys/geometry/ellipsoid.hpp"
#include "trackphys/geometry/triangle.hpp"

namespace trackphys::test {

struct Referenced {
    ReferenceContact contact;
    glm::dvec3 normal;  // world
    glm::dvec3 point;   // world
};

/// The long-double reference for a world configuration, in the ellipsoid's sorted frame.
inline Referenced reference(const Ellipsoid& e, const Triangle& t) {
    const glm::dmat3& m = e.sorted_axes();
    std::array<V3, 3> q;
    for (int i = 0; i < 3; ++i) {
        const V3 d{R(t[i].x) - R(e.center().x), R(t[i].y) - R(e.center().y),
                   R(t[i].z) - R(e.center().z)};
        q[i] = {d.x * m[0][0] + d.y * m[0][1] + d.z * m[0][2],
                d.x * m[1][0] + d.y * m[1][1] + d.z * m[1][2],
                d.x * m[2][0] + d.y * m[2][1] + d.z * m[2][2]};
    }
    const glm::dvec3 r = e.sorted_radii();
    ContactReference solver({R(r.x), R(r.y), R(r.z)}, q);
    Referenced out;
    out.contact = solver.solve();
    const V3 u = out.contact.u;
    const R hu = solver.h(u);
    const V3 local_point{-R(r.x) * R(r.x) * u.x / hu + out.contact.depth / 2 * u.x,
                         -R(r.y) * R(r.y) * u.y / hu + out.contact.depth / 2 * u.y,
                         -R(r.z) * R(r.z) * u.z / hu + out.contact.depth / 2 * u.z};
    for (int w = 0; w < 3; ++w) {
        out.normal[w] = double(m[0][w] * u.x + m[1][w] * u.y + m[2][w] * u.z);
        out.point[w] = double(R(e.center()[w]) + m[0][w] * local_point.x + m[1][w] * local_point.y +
                              m[2][w] * local_point.z);
    }
    return out;
}

}  // namespace trackphys::test
