#include "geometry/contact_extremes.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

#include <glm/geometric.hpp>

#include "geometry/contact_kernel.hpp"
#include "trackphys/math/types.hpp"

namespace trackphys {
namespace {

/// The power of two p with x in [p, 2p), and 1/p, for a normal positive x: read from its
/// exponent bits (ilogb and ldexp are library calls, too slow for every contact).
struct PowerOfTwo {
    double value, inverse;
};

PowerOfTwo power_of_two_below(double x) {
    constexpr std::uint64_t kExponentBits = 0x7ff0000000000000;
    const std::uint64_t exponent = std::bit_cast<std::uint64_t>(x) & kExponentBits;
    // Biased exponent E gives 2^(E - 1023); its inverse has biased exponent 2046 - E.
    return {std::bit_cast<double>(exponent),
            std::bit_cast<double>((std::uint64_t{2046} << 52) - exponent)};
}

/// Closest point of triangle (a, b, c) to p by its Voronoi regions (Ericson, "Real-Time
/// Collision Detection", 5.1.5), every division guarded so that degenerate triangles give a
/// point of their hull.
glm::dvec3 closest_point_on_triangle(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b,
                                     const glm::dvec3& c) {
    const glm::dvec3 ab = b - a, ac = c - a, ap = p - a;
    const double d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
    if (d1 <= 0.0 && d2 <= 0.0) return a;
    const glm::dvec3 bp = p - b;
    const double d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
    if (d3 >= 0.0 && d4 <= d3) return b;
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 && d1 - d3 > 0.0) return a + ab * (d1 / (d1 - d3));
    const glm::dvec3 cp = p - c;
    const double d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
    if (d6 >= 0.0 && d5 <= d6) return c;
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 && d2 - d6 > 0.0) return a + ac * (d2 / (d2 - d6));
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0 && (d4 - d3) + (d5 - d6) > 0.0)
        return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
    const double sum = va + vb + vc;
    if (!(sum > 0.0)) return a;
    return a + ab * (vb / sum) + ac * (vc / sum);
}

/// Scales v to unit length and sets length to its former length; false (v unchanged) for
/// the zero vector. The center can sit far below the scale that brings the triangle near 1
/// (c ~ 1e-159 when the triangle spans 1e170 around a center at 1e11): squaring such
/// components gives subnormals, whose lost bits left a direction 2e-7 off unit (found by
/// fuzz_contact). Dividing by the largest component first keeps the squares in [0, 3].
bool unit_and_length(glm::dvec3& v, double& length) {
    const double largest = std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
    if (!(largest > 0.0)) return false;
    v /= largest;
    const double scaled = glm::length(v);
    v /= scaled;
    length = largest * scaled;
    return true;
}

/// x clamped to the finite doubles. Coordinates may lie anywhere in double's range, so the
/// lengths between them may not: a center near -1.6e308 and a triangle near 0 in x and z
/// are 2.2e308 apart (found by fuzz_contact), and the ellipsoid's extreme point, half of
/// Contact::point, may lie a radius beyond the largest double. (An overlap is at most the
/// largest radius: moving the ellipsoid that far along the triangle's normal, away from its
/// plane, separates them.) Such a depth or point coordinate saturates at +-1.8e308 instead
/// of overflowing to an infinity, which contact.hpp reserves for non-finite triangles.
double saturated(double x) {
    constexpr double kLargest = std::numeric_limits<double>::max();
    return std::clamp(x, -kLargest, kLargest);
}

/// s * p for a power of two s, each coordinate saturated.
glm::dvec3 saturated_scaled(double s, const glm::dvec3& p) {
    return {saturated(s * p.x), saturated(s * p.y), saturated(s * p.z)};
}

/// For configurations whose lengths span more than double's squares can hold (the ellipsoid
/// smaller than 1e-60 of the triangle's distance or size): the ellipsoid acts as its center
/// point, sigma = h(u) - |c - z| with z the triangle's closest point and u = (c - z) / |c - z|.
/// The neglected terms are far below one ulp of the distances involved. The lengths are in
/// units of scale (a power of two, so the units change no rounding) until the end, where
/// they may leave double's range.
Contact point_like_contact(const Ellipsoid& ellipsoid, const std::array<glm::dvec3, 3>& v,
                           double scale) {
    const glm::dvec3 c = ellipsoid.center() / scale;
    std::array<glm::dvec3, 3> w;
    for (int i = 0; i < 3; ++i) w[i] = v[i] / scale;
    const glm::dvec3 z = closest_point_on_triangle(c, w[0], w[1], w[2]);
    glm::dvec3 u = c - z;
    double distance = 0.0;
    if (!unit_and_length(u, distance)) {
        u = glm::cross(w[1] - w[0], w[2] - w[0]);
        double length = 0.0;
        if (!unit_and_length(u, length)) u = glm::dvec3(0.0, 1.0, 0.0);
    }
    const glm::dvec3 local = u * ellipsoid.sorted_axes();
    const glm::dvec3 r = ellipsoid.sorted_radii();
    const double h = r.x * glm::length(r / r.x * local);
    // h / scale may lose bits as a subnormal, but only where h is below 2^-1022 of the
    // configuration, far below the rounding of z; the depth keeps h itself.
    const double half_depth = 0.5 * (h / scale - distance);
    return {saturated(h - distance * scale), u, saturated_scaled(scale, z + half_depth * u)};
}

}  // namespace

/// Solved at a power-of-two scale (exact) that brings the largest length near 1. Radii
/// below 2^-200 of the largest are raised to it (sigma moves by less than that, far below
/// one ulp of the largest radius), and an ellipsoid that is still below 2^-200 of the
/// configuration acts as a point.
Contact detail::rescaled_contact(const Ellipsoid& ellipsoid, const std::array<glm::dvec3, 3>& v) {
    const glm::dvec3& c = ellipsoid.center();
    const glm::dmat3& axes = ellipsoid.sorted_axes();
    const glm::dvec3 radii =
        glm::max(ellipsoid.sorted_radii(), glm::dvec3(ellipsoid.sorted_radii().x * 0x1p-200));
    double raw_extent = radii.x;
    for (int i = 0; i < 3; ++i) {
        // max, not sum: a sum of two coordinates near 1.8e308 overflows (found by fuzz_contact).
        const glm::dvec3 d = glm::max(abs_each(v[i]), abs_each(c));
        raw_extent = std::max({raw_extent, d.x, d.y, d.z});
    }
    const double scale = std::ldexp(1.0, std::ilogb(raw_extent));
    if (radii.z / scale < 0x1p-200) return point_like_contact(ellipsoid, v, scale);
    const glm::dvec3 center = c / scale;
    detail::LocalTriangle local;
    // Components below 2^-200 of the scale are flushed to zero, as the radii are raised
    // above: each vertex moves by less than 2^-199 of the largest length, and sigma with it
    // (1-Lipschitz), while subnormal components (a center 1e-303 from the triangle beside
    // a 1e9 m radius: found by fuzz_contact) would break the solver's squares into an
    // infinite depth.
    // The ellipsoid and the triangle's offsets from its center can still be far below the
    // largest coordinate (radii 6e257 m beside a vertex at -3.5e296 m: 1e-39 here, and a
    // normal 0.987 long; found by fuzz_contact), so the kernel runs where the largest radius
    // is in [1, 2): it forms products up to the sixth power of a length (h(N)^2 = |D N|^2
    // for the area normal N) and compares fourth powers, which stay normal numbers there
    // over every configuration this path admits (smallest radius within 2^-200 of the
    // largest, triangle within 2^206 of it). Powers of two scale every rounding exactly, so
    // the result is bit-identical to the fast path's wherever both apply.
    const glm::dvec3 local_radii = radii / scale;
    const PowerOfTwo unit = power_of_two_below(local_radii.x);
    for (int i = 0; i < 3; ++i) {
        local.q[i] = (v[i] / scale - center) * axes;
        for (int k = 0; k < 3; ++k)
            if (std::abs(local.q[i][k]) < 0x1p-200) local.q[i][k] = 0.0;
        local.q[i] *= unit.inverse;
    }
    const glm::dvec3 sum = abs_each(local.q[0]) + abs_each(local.q[1]) + abs_each(local.q[2]);
    local.extent = sum.x + sum.y + sum.z;
    for (int i = 0; i < 3; ++i) local.edge[i] = local.q[(i + 1) % 3] - local.q[i];
    const detail::LocalContact solved =
        detail::contact_in_sorted_frame(local_radii * unit.inverse, local);
    const double back = unit.value * scale;  // a power of two: exact
    // The point as the center plus its offset, unless the offset alone leaves double's range
    // (a center near -1.6e308 and a triangle near 1e308): then formed in units of back, where
    // the center's lost bits (below 2^-1022 back) are far below the offset's rounding.
    const glm::dvec3 offset = axes * solved.point;
    glm::dvec3 point = c + back * offset;
    for (int k = 0; k < 3; ++k)
        if (!std::isfinite(point[k])) point[k] = saturated(back * (c[k] / back + offset[k]));
    return {saturated(solved.depth * back), axes * solved.u, point};
}

}  // namespace trackphys
