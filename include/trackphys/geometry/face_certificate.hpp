#pragma once

#include <cmath>
#include <optional>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>

#include "trackphys/geometry/contact.hpp"
#include "trackphys/geometry/ellipsoid.hpp"
#include "trackphys/geometry/normalized_triangle.hpp"
#include "trackphys/math/types.hpp"

namespace trackphys {

/// A contact with the ellipsoid's support along its normal, h(normal) =
/// support_extent(ellipsoid, normal), to the bit: what depth_bound_along needs to bound the
/// other triangles along that normal.
struct ContactWithSupport : Contact {
    double support;  ///< h(normal) (m)
};

/// The exact contact of the ellipsoid with the triangle when its face decides it, proved by
/// the kernel's face certificate (docs/design.md#the-face-certificate-in-the-triangles-frame);
/// nullopt when the proof does not hold with a margin for rounding, and then
/// ellipsoid_triangle_contact must decide. Where it answers, it is that kernel's answer to
/// rounding, with its conventions: depth = sigma, normal = the side of the triangle's plane
/// the centre lies on, point = the midpoint of the ellipsoid's extreme point towards the
/// plane and the touching point.
///
/// It works in the triangle's frame, as the cull does (ellipsoid_depth_bound): the push
/// direction is u = +-normal, g(u) = h(u) - |z| with z the centre's height over the plane,
/// and the touching point z(u) = x(-u) + g u, with x(-u) = -A D^2 A^T u / h(u), lies in the
/// plane at the centre's in-plane coordinates plus x(-u)'s. The certificate holds when that
/// point lies in the triangle and g h(u) < r_min^2 (the closest regime; every separated
/// pair and every shallow contact): then sigma = g(u). The support it returns is h(u), which
/// the proof computes anyway, by support_extent's operations.
inline std::optional<ContactWithSupport> certified_face_contact(const NormalizedTriangle& t,
                                                                const Ellipsoid& e) {
    const glm::dvec3 local = e.center() - t.origin;
    const double z = glm::dot(t.normal, local);
    const double x = glm::dot(t.dir_x, local);
    const double y = glm::dot(t.dir_y, local);
    const glm::dvec3& r = e.sorted_radii();
    const glm::dmat3& axes = e.sorted_axes();
    // Push away from the plane, towards the centre's side. z = 0 puts g = h(u) >= r_min,
    // outside the closest regime, so the tie needs no rule.
    const glm::dvec3 u = z >= 0.0 ? t.normal : -t.normal;
    const glm::dvec3 stretched = r * (u * axes);  // D A^T u
    const double h = glm::length(stretched);
    const double g = h - std::abs(z);
    const glm::dvec3 extreme = axes * (r * stretched) * (-1.0 / h);  // x(-u), from the centre
    const double px = x + glm::dot(t.dir_x, extreme);
    const double py = y + glm::dot(t.dir_y, extreme);

    // The margin. S bounds every length formed here. x, y, z and the extreme point carry a
    // few eps S of rounding; the frame is the triangle's to rounding too, but its normal (a
    // cross product of the edges) is off by ~eps / sin of the angle at the origin, which
    // the sliver guard keeps below 2^10 eps, tilting the plane by that times S at the
    // touching point. Together below 2^13 eps S = 2^-39 S: the margin takes 8 times that.
    // The edge tests compare cross products, whose rounding is S times the edge's length:
    // scaled by the edge's L1 length (at least its length), they demand a distance of at
    // least the margin from each edge. The regime test adds the margin to g.
    const double scale = std::abs(x) + std::abs(y) + std::abs(z) + t.x1 + r.x;
    const double margin = 0x1p-36 * scale;
    // The normal's tilt, up to ~eps x1 / y2, also moves the answer by about that times S:
    // past 2e5 m of S x1 / y2 (a thin triangle kilometres long) that nears the kernel's
    // 1e-9 m, so such a triangle is left to the kernel too.
    const bool thick = t.y2 >= 0x1p-10 * t.x1 && scale * t.x1 <= 2e5 * t.y2;
    // Vertices (0, 0), (x1, 0), (x2, y2), counter-clockwise: left of each edge.
    const bool off_first = py >= margin;
    const bool off_second =
        (t.x2 - t.x1) * py - t.y2 * (px - t.x1) >= margin * (t.x1 - t.x2 + t.y2);
    const bool off_third = t.y2 * px - t.x2 * py >= margin * (t.x2 + t.y2);
    const bool closest = (g + margin) * h * (1.0 + 0x1p-36) < r.z * r.z;
    // Any NaN fails every comparison and refuses.
    if (!(thick && off_first && off_second && off_third && closest)) return std::nullopt;
    return ContactWithSupport{{g, u, e.center() + extreme + (0.5 * g) * u}, h};
}

}  // namespace trackphys
