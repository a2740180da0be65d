// libFuzzer target: the exact ellipsoid-triangle contact kernel.
//
// Bytes -> an ellipsoid (through Ellipsoid::make: rejections are fine) and a triangle ->
// ellipsoid_triangle_contact. Byte 0 picks the decoding:
// - even: 19 little-endian int16, a 1/256 m grid for the center and vertices (+-128 m),
//   (1 + u) / 1024 m for the radii, raw integers for the quaternion. A grid makes the
//   special cases the kernel must get right (touching, coincident or collinear vertices,
//   equal radii, axis-aligned faces) easy for the fuzzer to reach.
// - odd: 19 raw doubles (any bit pattern: NaN, infinities, subnormals, 1e308).
//
// Every contact must be finite (depth -infinity only for a triangle with a non-finite
// coordinate, as contact.hpp documents) with a unit normal. For moderate sizes (see
// is_moderate) the depth must also pass three independent checks:
// 1. Gauge bound. In the sorted frame scaled by 1/radii the ellipsoid is the unit ball; if
//    the scaled triangle's distance from the origin is d, the triangle touches the
//    ellipsoid scaled by d about its center, and comparing that with E + t*ball (r_min*E
//    inside ball inside r_max*E, for the unit-radius ball) bounds the signed depth:
//    (1 - d) * r_min <= depth <= (1 - d) * r_max   when d <= 1 (overlap),
//    (1 - d) * r_max <= depth <= (1 - d) * r_min   when d >= 1 (apart).
//    For a sphere the bound is the exact answer.
// 2. Invariance: every vertex order, and the same ellipsoid rebuilt from its sorted axes
//    and radii, give the same depth.
// 3. The normal is the minimum translation direction: moving the ellipsoid by depth along
//    it leaves them just touching (depth 0, up to |depth| times the normal's angular error),
//    since depth is 1-Lipschitz in translation and decreases at exactly unit rate along the
//    optimal direction.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <optional>
#include <string>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

#include "trackphys/geometry/contact.hpp"
#include "trackphys/geometry/ellipsoid.hpp"
#include "trackphys/geometry/triangle.hpp"
#include "trackphys/math/types.hpp"

namespace {

using glm::dvec3;
using trackphys::Contact;
using trackphys::Ellipsoid;
using trackphys::Triangle;

constexpr std::size_t kValues = 19;  // center 3, quaternion 4, radii 3, vertices 9
constexpr double kEps = std::numeric_limits<double>::epsilon();
// The accuracy contract (docs/design.md#exactness-promises-and-their-tests): depth within
// 1e-9 m of the truth.
constexpr double kContract = 1e-9;

[[noreturn]] void finding(const char* what, const Ellipsoid& e, const Triangle& t,
                          const Contact& c) {
    const dvec3 r = e.semi_axes();
    const glm::dquat q = e.orientation();
    std::fprintf(stderr,
                 "fuzz_contact: %s\n  center (%.17g, %.17g, %.17g)\n"
                 "  orientation (w %.17g, %.17g, %.17g, %.17g)\n"
                 "  semi-axes (%.17g, %.17g, %.17g)\n",
                 what, e.center().x, e.center().y, e.center().z, q.w, q.x, q.y, q.z, r.x, r.y, r.z);
    for (int i = 0; i < 3; ++i)
        std::fprintf(stderr, "  vertex %d (%.17g, %.17g, %.17g)\n", i, t[i].x, t[i].y, t[i].z);
    std::fprintf(stderr, "  depth %.17g normal (%.17g, %.17g, %.17g) point (%.17g, %.17g, %.17g)\n",
                 c.depth, c.normal.x, c.normal.y, c.normal.z, c.point.x, c.point.y, c.point.z);
    std::abort();
}

struct Decoded {
    dvec3 center;
    glm::dquat orientation;
    dvec3 semi_axes;
    std::array<dvec3, 3> vertices;
};

Decoded decode(const std::uint8_t* data, std::size_t size) {
    std::array<double, kValues> v{};
    if (data[0] % 2 == 0) {
        for (std::size_t i = 0; i < kValues; ++i) {
            std::int16_t n = 0;
            if (1 + 2 * i + 2 <= size) std::memcpy(&n, data + 1 + 2 * i, 2);
            v[i] = n;
        }
        for (std::size_t i : {0u, 1u, 2u}) v[i] /= 256.0;
        for (std::size_t i = 7; i < 10; ++i) v[i] = (std::abs(v[i]) + 1.0) / 1024.0;
        for (std::size_t i = 10; i < kValues; ++i) v[i] /= 256.0;
    } else {
        for (std::size_t i = 0; i < kValues; ++i)
            if (1 + 8 * i + 8 <= size) std::memcpy(&v[i], data + 1 + 8 * i, 8);
    }
    return {dvec3(v[0], v[1], v[2]),
            glm::dquat(v[3], v[4], v[5], v[6]),
            dvec3(v[7], v[8], v[9]),
            {dvec3(v[10], v[11], v[12]), dvec3(v[13], v[14], v[15]), dvec3(v[16], v[17], v[18])}};
}

bool finite_triangle(const Triangle& t) {
    return trackphys::is_finite(t[0]) && trackphys::is_finite(t[1]) && trackphys::is_finite(t[2]);
}

void check_finite(const Ellipsoid& e, const Triangle& t, const Contact& c) {
    if (!trackphys::is_finite(c.normal) || !trackphys::is_finite(c.point))
        finding("non-finite normal or point", e, t, c);
    if (std::abs(glm::length(c.normal) - 1.0) > 1e-9) finding("normal is not unit", e, t, c);
    if (finite_triangle(t)) {
        if (!std::isfinite(c.depth)) finding("non-finite depth for a finite triangle", e, t, c);
    } else if (c.depth != -std::numeric_limits<double>::infinity()) {
        finding("a non-finite triangle must give depth -infinity", e, t, c);
    }
}

// Sizes at which a double computation of the checks is accurate to well under the contract:
// radii in [1e-3, 1e3] m, vertices within 1e3 m of the center, the center within 1e5 m of the
// origin (a 20 km world: docs/design.md#conventions).
bool is_moderate(const Ellipsoid& e, const Triangle& t) {
    const dvec3& r = e.sorted_radii();
    if (!(r.z >= 1e-3 && r.x <= 1e3 && glm::length(e.center()) <= 1e5)) return false;
    for (int i = 0; i < 3; ++i)
        if (!(glm::length(t[i] - e.center()) <= 1e3)) return false;
    return true;
}

// Distance from the origin to segment [a, b].
double segment_distance(const dvec3& a, const dvec3& b) {
    const dvec3 ab = b - a;
    const double len2 = glm::dot(ab, ab);
    const double s = len2 > 0.0 ? std::clamp(-glm::dot(a, ab) / len2, 0.0, 1.0) : 0.0;
    return glm::length(a + s * ab);
}

// Distance from the origin to triangle s: the nearest of the edges, or of the origin's
// projection onto the plane when it falls inside. The projection is measured as the point
// a + s ab + t ac rebuilt from its barycentric coordinates, a point of the triangle: on a
// nearly degenerate triangle the rounded normal is meaningless, and the plane distance it
// gives could be far below the true one, while a point of the triangle never is.
double origin_distance(const std::array<dvec3, 3>& s) {
    double d = std::min(
        {segment_distance(s[0], s[1]), segment_distance(s[1], s[2]), segment_distance(s[2], s[0])});
    const dvec3 ab = s[1] - s[0], ac = s[2] - s[0];
    const dvec3 n = glm::cross(ab, ac);
    const double n2 = glm::dot(n, n);
    if (n2 > 0.0) {
        const dvec3 p = (glm::dot(s[0], n) / n2) * n - s[0];  // projection, relative to a
        const double u = glm::dot(glm::cross(p, ac), n) / n2;
        const double v = glm::dot(glm::cross(ab, p), n) / n2;
        if (u >= 0.0 && v >= 0.0 && u + v <= 1.0)
            d = std::min(d, glm::length(s[0] + u * ab + v * ac));
    }
    return d;
}

void check_gauge_bound(const Ellipsoid& e, const Triangle& t, const Contact& c) {
    const dvec3& r = e.sorted_radii();
    std::array<dvec3, 3> s;
    double extent = 0.0;
    for (std::size_t i = 0; i < 3; ++i) {
        s[i] = e.to_sorted_local(t.vertices[i]) / r;
        extent = std::max(extent, glm::length(s[i]));
    }
    const double d = origin_distance(s);
    const double lo = (1.0 - d) * (d <= 1.0 ? r.z : r.x);
    const double hi = (1.0 - d) * (d <= 1.0 ? r.x : r.z);
    // The contract, plus the rounding of d (a few ulps of the scaled extent) times r_max.
    const double tolerance = kContract + 64.0 * kEps * (1.0 + extent) * r.x;
    if (c.depth < lo - tolerance || c.depth > hi + tolerance)
        finding("depth outside the gauge bound", e, t, c);
}

void check_same_depth(const char* what, const Ellipsoid& e, const Triangle& t, const Contact& c,
                      const Contact& other) {
    if (!(std::abs(other.depth - c.depth) <= 2.0 * kContract)) finding(what, e, t, c);
}

void check_invariance(const Ellipsoid& e, const Triangle& t, const Contact& c) {
    std::array<int, 3> order = {0, 1, 2};
    while (std::next_permutation(order.begin(), order.end())) {
        const Triangle permuted(t[order[0]], t[order[1]], t[order[2]]);
        check_same_depth("depth depends on the vertex order", e, t, c,
                         trackphys::ellipsoid_triangle_contact(e, permuted));
    }
    const Ellipsoid sorted(e.center(), glm::quat_cast(e.sorted_axes()), e.sorted_radii());
    check_same_depth("depth changes on the equivalent sorted-axes ellipsoid", e, t, c,
                     trackphys::ellipsoid_triangle_contact(sorted, t));
}

void check_normal(const Ellipsoid& e, const Triangle& t, const Contact& c) {
    const Ellipsoid moved = e.transformed(glm::dquat(1.0, 0.0, 0.0, 0.0), c.depth * c.normal);
    const Contact touching = trackphys::ellipsoid_triangle_contact(moved, t);
    // A normal off the optimal direction by an angle a moves the result by up to
    // |depth| a (depth is 1-Lipschitz): the contract allows a = 1e-6 rad (README.md). And
    // translating by depth rounds the center: a few ulps of its size.
    const double slack =
        1e-6 * std::abs(c.depth) + 8.0 * kEps * (glm::length(e.center()) + std::abs(c.depth));
    if (!(std::abs(touching.depth) <= 2.0 * kContract + slack))
        finding("moving by depth along the normal does not leave them touching", e, t, c);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size < 1 || size > 1 + 8 * kValues) return -1;
    const Decoded in = decode(data, size);
    const std::optional<Ellipsoid> ellipsoid =
        Ellipsoid::make(in.center, in.orientation, in.semi_axes);
    if (!ellipsoid) return 0;  // a defined rejection
    const Triangle triangle(in.vertices[0], in.vertices[1], in.vertices[2]);
    const Contact contact = trackphys::ellipsoid_triangle_contact(*ellipsoid, triangle);
    check_finite(*ellipsoid, triangle, contact);
    if (finite_triangle(triangle) && is_moderate(*ellipsoid, triangle)) {
        check_gauge_bound(*ellipsoid, triangle, contact);
        check_invariance(*ellipsoid, triangle, contact);
        check_normal(*ellipsoid, triangle, contact);
    }
    return 0;
}
