// libFuzzer target: the exact ellipsoid-ellipsoid contact.
//
// Bytes -> two ellipsoids (through Ellipsoid::make: rejections are fine) ->
// ellipsoid_ellipsoid_contact. Byte 0 picks the decoding:
// - even: 20 little-endian int16, a 1/256 m grid for the centres (+-128 m), (1 + u) / 1024 m
//   for the radii, raw integers for the quaternions: touching, coincident, equal and
//   axis-aligned configurations are easy to reach;
// - odd: 20 raw doubles (any bit pattern: NaN, infinities, subnormals, 1e308).
//
// Every contact must be free of NaN with a unit normal, finite when both solids lie within
// the doubles' range, and the same with the arguments swapped (normal negated, bit for
// bit). For moderate sizes (every length within 2^-20..2^20 m) the depth must also pass
// independent checks:
// 1. Bounding balls: each ellipsoid holds the ball of its smallest semi-axis and lies in the
//    ball of its largest, so r_min,A + r_min,B - |d| <= depth <= r_max,A + r_max,B - |d|.
// 2. Upper bound: depth is the minimum of h, so no probed direction (the centre line, the
//    axes of both, the normal itself) gives less, and -normal gives depth itself.
// 3. The normal is the minimum translation direction: moving a by depth along it leaves
//    them just touching (depth 0), overlapping or apart.
// 4. The solver's proven lower bound (detail::pair_solution, also for an answer the search
//    could not prove, PairPath::unproven) is at most the depth and at most h in every
//    probed direction.

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <optional>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

#include "geometry/ellipsoid_pair_kernel.hpp"
#include "trackphys/geometry/ellipsoid_pair.hpp"

namespace {

using glm::dvec3;
using trackphys::Contact;
using trackphys::Ellipsoid;

constexpr std::size_t kValues = 20;  // per ellipsoid: center 3, quaternion 4, radii 3

void describe(const char* name, const Ellipsoid& e) {
    std::fprintf(stderr, "%s: c (%a %a %a) q (%a %a %a %a) axes (%a %a %a)\n", name, e.center().x,
                 e.center().y, e.center().z, e.orientation().w, e.orientation().x,
                 e.orientation().y, e.orientation().z, e.semi_axes().x, e.semi_axes().y,
                 e.semi_axes().z);
}

[[noreturn]] void finding(const char* what, const Ellipsoid& a, const Ellipsoid& b,
                          const Contact& c) {
    std::fprintf(stderr, "fuzz_ellipsoid_pair: %s\n", what);
    describe("a", a);
    describe("b", b);
    std::fprintf(stderr, "depth %.17g normal (%.17g %.17g %.17g) point (%.17g %.17g %.17g)\n",
                 c.depth, c.normal.x, c.normal.y, c.normal.z, c.point.x, c.point.y, c.point.z);
    std::abort();
}

std::optional<std::array<double, kValues>> decode(const std::uint8_t* data, std::size_t size) {
    std::array<double, kValues> v{};
    if (size < 1) return std::nullopt;
    const bool raw = data[0] & 1;
    ++data;
    --size;
    if (raw) {
        if (size < kValues * sizeof(double)) return std::nullopt;
        std::memcpy(v.data(), data, kValues * sizeof(double));
        return v;
    }
    if (size < kValues * 2) return std::nullopt;
    for (std::size_t i = 0; i < kValues; ++i) {
        const auto u = static_cast<std::int16_t>(data[2 * i] | (data[2 * i + 1] << 8));
        const std::size_t slot = i % 10;
        v[i] = slot < 3 ? u / 256.0 : slot < 7 ? double(u) : (1.0 + std::abs(double(u))) / 1024.0;
    }
    return v;
}

std::optional<Ellipsoid> ellipsoid(const std::array<double, kValues>& v, std::size_t first) {
    const double* p = v.data() + first;
    return Ellipsoid::make({p[0], p[1], p[2]}, glm::dquat(p[3], p[4], p[5], p[6]),
                           {p[7], p[8], p[9]});
}

/// h of the pair at unit n in double (the support of A - B).
double support(const Ellipsoid& a, const Ellipsoid& b, const dvec3& n) {
    const auto one = [](const Ellipsoid& e, const dvec3& m) {
        const dvec3 local = m * e.sorted_axes();
        const dvec3 r = e.sorted_radii() * local;
        return std::sqrt(glm::dot(r, r));
    };
    return glm::dot(a.center() - b.center(), n) + one(a, n) + one(b, n);
}

bool moderate(const Ellipsoid& e) {
    const dvec3 m = glm::abs(e.center());
    return e.sorted_radii().z >= 0x1p-20 && e.sorted_radii().x <= 0x1p20 &&
           std::max({m.x, m.y, m.z}) <= 0x1p20;
}

bool within_range(const Ellipsoid& e) {
    const dvec3 m = glm::abs(e.center());
    return std::max({m.x, m.y, m.z}) + e.bounding_radius() < std::numeric_limits<double>::max();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const auto values = decode(data, size);
    if (!values) return 0;
    const auto a = ellipsoid(*values, 0), b = ellipsoid(*values, 10);
    if (!a || !b) return 0;
    const Contact c = trackphys::ellipsoid_ellipsoid_contact(*a, *b);
    if (std::isnan(c.depth) || std::isnan(c.point.x) || std::isnan(c.point.y) ||
        std::isnan(c.point.z))
        finding("NaN", *a, *b, c);
    if (!(std::abs(glm::length(c.normal) - 1.0) <= 1e-12)) finding("normal not unit", *a, *b, c);
    if (within_range(*a) && within_range(*b) &&
        !(std::isfinite(c.depth) && std::isfinite(c.point.x) && std::isfinite(c.point.y) &&
          std::isfinite(c.point.z)))
        finding("not finite", *a, *b, c);
    const Contact s = trackphys::ellipsoid_ellipsoid_contact(*b, *a);
    if (std::bit_cast<std::uint64_t>(s.depth) != std::bit_cast<std::uint64_t>(c.depth) ||
        std::memcmp(&s.point, &c.point, sizeof c.point) != 0 ||
        (std::memcmp(&*a, &*b, sizeof(Ellipsoid)) != 0 && s.normal != -c.normal))
        finding("swapping the arguments changed more than the normal", *a, *b, c);
    if (!moderate(*a) || !moderate(*b)) return 0;

    const double largest = std::max(a->bounding_radius(), b->bounding_radius());
    const double tolerance = 1e-9 * std::max(1.0, largest);
    const double distance = glm::distance(a->center(), b->center());
    const double lowest = a->sorted_radii().z + b->sorted_radii().z - distance;
    const double highest = a->sorted_radii().x + b->sorted_radii().x - distance;
    if (!(c.depth >= lowest - tolerance && c.depth <= highest + tolerance))
        finding("depth outside the bounding balls' bounds", *a, *b, c);
    if (!(std::abs(support(*a, *b, -c.normal) - c.depth) <= tolerance))
        finding("h at the normal is not the depth", *a, *b, c);
    // The solution is at the frame's power-of-two scale: the ratio of the depths is it.
    const trackphys::detail::PairSolution solution = trackphys::detail::pair_solution(*a, *b);
    const double unit = c.depth / solution.depth;
    const bool scaled = std::isfinite(unit) && unit > 0.0;
    const double floor = scaled ? solution.lower_bound * unit : -INFINITY;
    if (!(solution.lower_bound <= solution.depth))
        finding("the proven lower bound is above the depth", *a, *b, c);
    std::array<dvec3, 7> probes{};
    probes[0] = distance > 0 ? (b->center() - a->center()) / distance : dvec3(1.0, 0.0, 0.0);
    for (int i = 0; i < 3; ++i) {
        probes[1 + i] = a->sorted_axes()[i];
        probes[4 + i] = b->sorted_axes()[i];
    }
    for (const dvec3& n : probes) {
        if (!(support(*a, *b, n) >= c.depth - tolerance &&
              support(*a, *b, -n) >= c.depth - tolerance))
            finding("a probed direction is below the depth", *a, *b, c);
        if (!(support(*a, *b, n) >= floor - tolerance && support(*a, *b, -n) >= floor - tolerance))
            finding("a probed direction is below the proven lower bound", *a, *b, c);
    }
    const Ellipsoid moved(a->center() + c.depth * c.normal, a->orientation(), a->semi_axes());
    const Contact touching = trackphys::ellipsoid_ellipsoid_contact(moved, *b);
    if (!(std::abs(touching.depth) <= tolerance + 1e-12 * std::abs(c.depth)))
        finding("moving by depth along the normal does not leave them touching", *a, *b, c);
    return 0;
}
