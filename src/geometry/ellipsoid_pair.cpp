#include "trackphys/geometry/ellipsoid_pair.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <stdexcept>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "geometry/ellipsoid_pair_kernel.hpp"
#include "trackphys/math/types.hpp"

// The public entries: each orders the pair, moves it into the first ellipsoid's sorted frame
// at unit scale (a rotation and a power of two, which keep the answer) and maps the solution
// back (docs/ellipsoid_pair.md); the batch solves the frames' common path in lanes.

namespace trackphys {
namespace {

/// The bits of an ellipsoid's defining numbers, for a total order independent of the
/// argument order (so that a <-> b runs the very same arithmetic).
std::array<std::uint64_t, 10> key(const Ellipsoid& e) {
    const glm::dvec3& c = e.center();
    const glm::dvec3& r = e.semi_axes();
    const glm::dquat& q = e.orientation();
    std::array<std::uint64_t, 10> k{};
    const std::array<double, 10> v = {c.x, c.y, c.z, r.x, r.y, r.z, q.w, q.x, q.y, q.z};
    for (std::size_t i = 0; i < v.size(); ++i) k[i] = std::bit_cast<std::uint64_t>(v[i]);
    return k;
}

// Radii below 2^-200 of the larger semi-axis are raised to it: that moves the answer by
// less than an ulp and keeps every support value a normal number.
constexpr double kSmallestRadius = 0x1p-200;
// Beyond this distance between the centres (at unit scale) the support of each ellipsoid
// along the centre line is exact to far below an ulp of the distance.
constexpr double kFarField = 0x1p500;

glm::dvec3 raised(const glm::dvec3& r) { return glm::max(r, glm::dvec3(kSmallestRadius)); }

/// Both centres so far apart (relative to the radii) that the solver's products would
/// overflow: the minimiser is the centre line to within 2^-500 rad.
Contact far_field(const Ellipsoid& a, const Ellipsoid& b, double scale) {
    const glm::dvec3 half = a.center() * 0.5 - b.center() * 0.5;  // never overflows
    const glm::dvec3 m = abs_each(half);
    const double largest = std::max({m.x, m.y, m.z});
    const glm::dvec3 u = glm::normalize(half / largest);  // from b towards a
    const auto support = [&](const Ellipsoid& e, const glm::dvec3& n) {
        const glm::dvec3 local = n * e.sorted_axes();
        const glm::dvec3 r = raised(e.sorted_radii() / scale);
        const glm::dvec3 m2 = r * r * local;
        const double value = std::sqrt(glm::dot(m2, local));
        return std::pair{value, e.sorted_axes() * (m2 / value) * scale};
    };
    const auto [ha, xa] = support(a, -u);
    const auto [hb, xb] = support(b, u);
    const double distance = 2.0 * largest * glm::length(half / largest);
    const glm::dvec3 point = a.center() * 0.5 + b.center() * 0.5 + 0.5 * (xa + xb);
    return {-(distance - (ha + hb) * scale), u, point};
}

/// The power of two that brings r (> 0, finite) into [1, 2): its exponent bits, or for a
/// subnormal r the library's ldexp (a call, and rare).
double unit_scale(double r) {
    const std::uint64_t exponent = std::bit_cast<std::uint64_t>(r) & 0x7ff0000000000000u;
    return exponent != 0 ? std::bit_cast<double>(exponent) : std::ldexp(1.0, std::ilogb(r));
}

/// 1 / s for a power of two s, exactly: from its exponent bits when 1 / s is a normal
/// number (every frame but the most extreme), so that the frame need not wait on a division.
double inverse_power_of_two(double s) {
    const std::uint64_t exponent = (std::bit_cast<std::uint64_t>(s) >> 52) & 0x7ff;
    return exponent >= 1 && exponent <= 2045 ? std::bit_cast<double>((2046 - exponent) << 52)
                                             : 1.0 / s;
}

/// a and b in a's sorted frame at unit scale, or false when their centres are too far apart.
bool unit_frame(const Ellipsoid& a, const Ellipsoid& b, double& scale, detail::PairFrame& frame) {
    scale = unit_scale(std::max(a.sorted_radii().x, b.sorted_radii().x));
    const double inv = inverse_power_of_two(scale);
    const glm::dvec3 d_world = (a.center() - b.center()) * inv;
    const glm::dvec3 d_abs = abs_each(d_world);
    if (!(std::max({d_abs.x, d_abs.y, d_abs.z}) < kFarField)) return false;
    const glm::dmat3& axes = a.sorted_axes();
    frame.ra = raised(a.sorted_radii() * inv);
    frame.rb = raised(b.sorted_radii() * inv);
    frame.b_axes = glm::transpose(axes) * b.sorted_axes();
    frame.d = d_world * axes;  // A^T d
    // B^T d from world space, beside A^T B rather than after it (the first guess needs it).
    frame.d_in_b = d_world * b.sorted_axes();
    return true;
}

/// The warm descent's start in a's sorted frame for the previous contact's normal of the
/// ordered pair (n = -normal points from a towards b), brought within the evaluation's
/// range; false for a zero, infinite or NaN one, which takes the cold path.
bool warm_start(const glm::dvec3& previous_normal, const glm::dmat3& axes, glm::dvec3& start) {
    start = -(previous_normal * axes);  // A^T n
    const double length2 = glm::dot(start, start);
    if (length2 >= 0x1p-60 && length2 <= 0x1p60) return true;
    if (std::isnan(length2)) return false;
    const glm::dvec3 m = abs_each(start);
    const double largest = std::max({m.x, m.y, m.z});
    if (!(largest > 0.0 && largest <= std::numeric_limits<double>::max())) return false;
    start /= largest;  // rare: a length outside 2^-30..2^30 or overflowing when squared
    return true;
}

/// A solution in a's sorted frame at unit scale back in world space; `swapped` when the
/// caller's arguments were the other way round, so that the normal points the other way.
/// The normal is turned here, before it leaves the registers: turning the returned Contact
/// in memory makes the caller's wide loads wait on this function's narrow stores. Forced
/// inline, so that the single call keeps its solution in registers although the batch calls
/// this too.
[[gnu::always_inline]] inline Contact world_contact(const Ellipsoid& a, const Ellipsoid& b,
                                                    bool swapped, double scale,
                                                    const detail::PairSolution& s) {
    const glm::dmat3& axes = a.sorted_axes();
    const glm::dvec3 extreme_a = a.center() + axes * s.extreme_a * scale;
    const glm::dvec3 extreme_b = b.center() + axes * s.extreme_b * scale;
    const glm::dvec3 towards_b = axes * s.n;  // the normal of the swapped pair
    // Halves first: the sum of two points near the largest double would overflow.
    return {s.depth * scale, swapped ? towards_b : -towards_b, 0.5 * extreme_a + 0.5 * extreme_b};
}

/// The contact of a and b, which come in key order (`swapped` as for world_contact); `solve`
/// maps the frame to the solution (cold or warm).
template <class Solve>
Contact ordered_contact(const Ellipsoid& a, const Ellipsoid& b, bool swapped, Solve solve) {
    double scale;
    detail::PairFrame frame;
    if (!unit_frame(a, b, scale, frame)) {
        Contact far = far_field(a, b, scale);
        if (swapped) far.normal = -far.normal;
        return far;
    }
    return world_contact(a, b, swapped, scale, solve(frame));
}

/// The solver for the ordered pair (first, ...) started from the caller's previous normal,
/// negated when the pair was swapped (so that (b, a, -normal) runs as (a, b, normal)).
auto warm_solver(const Ellipsoid& first, const glm::dvec3& previous_normal, bool swapped) {
    return [&first, &previous_normal, swapped](const detail::PairFrame& frame) {
        glm::dvec3 start;
        const glm::dvec3 normal = swapped ? -previous_normal : previous_normal;
        return warm_start(normal, first.sorted_axes(), start) ? detail::solve_pair(frame, start)
                                                              : detail::solve_pair(frame);
    };
}

const auto cold_solver = [](const detail::PairFrame& frame) { return detail::solve_pair(frame); };

/// A pair of the batch in key order, and its frame's scale.
struct OrderedPair {
    const Ellipsoid* a;
    const Ellipsoid* b;
    bool swapped;
    double scale;
    std::size_t index;  // in the batch
};

// The batch runs in chunks of this many pairs, its frames and solutions on the stack.
constexpr std::size_t kChunk = 64;

/// ellipsoid_ellipsoid_contacts over one chunk: the frames in scalar code (a far-field pair
/// takes the single call), the common path in lanes, solve_pair for the pairs it leaves.
void contacts_chunk(std::span<const Ellipsoid> a, std::span<const Ellipsoid> b,
                    std::span<Contact> contacts) {
    std::array<OrderedPair, kChunk> pairs;
    std::array<detail::PairFrame, kChunk> frames;
    std::array<detail::PairSolution, kChunk> solutions;
    std::array<bool, kChunk> kept;
    std::size_t framed = 0;
    for (std::size_t i = 0; i < a.size(); ++i) {
        const bool swapped = key(b[i]) < key(a[i]);
        OrderedPair& p = pairs[framed];
        p = {swapped ? &b[i] : &a[i], swapped ? &a[i] : &b[i], swapped, 0.0, i};
        if (unit_frame(*p.a, *p.b, p.scale, frames[framed]))
            ++framed;
        else
            contacts[i] = ellipsoid_ellipsoid_contact(a[i], b[i]);
    }
    detail::solve_pairs_on_common_path(std::span(frames.data(), framed),
                                       std::span(solutions.data(), framed),
                                       std::span(kept.data(), framed));
    for (std::size_t j = 0; j < framed; ++j) {
        const OrderedPair& p = pairs[j];
        if (!kept[j]) solutions[j] = detail::solve_pair(frames[j]);
        contacts[p.index] = world_contact(*p.a, *p.b, p.swapped, p.scale, solutions[j]);
    }
}

}  // namespace

Contact ellipsoid_ellipsoid_contact(const Ellipsoid& a, const Ellipsoid& b) {
    const bool swapped = key(b) < key(a);
    return ordered_contact(swapped ? b : a, swapped ? a : b, swapped, cold_solver);
}

Contact ellipsoid_ellipsoid_contact(const Ellipsoid& a, const Ellipsoid& b,
                                    const glm::dvec3& previous_normal) {
    const bool swapped = key(b) < key(a);
    const Ellipsoid& first = swapped ? b : a;
    return ordered_contact(first, swapped ? a : b, swapped,
                           warm_solver(first, previous_normal, swapped));
}

void ellipsoid_ellipsoid_contacts(std::span<const Ellipsoid> a, std::span<const Ellipsoid> b,
                                  std::span<Contact> contacts) {
    if (a.size() != b.size() || a.size() != contacts.size())
        throw std::invalid_argument("ellipsoid_ellipsoid_contacts: spans of different sizes");
    // One pair: the single call, without the chunk's arrays and the lanes' dispatch.
    if (a.size() == 1) {
        contacts[0] = ellipsoid_ellipsoid_contact(a[0], b[0]);
        return;
    }
    for (std::size_t start = 0; start < a.size(); start += kChunk) {
        const std::size_t count = std::min(kChunk, a.size() - start);
        contacts_chunk(a.subspan(start, count), b.subspan(start, count),
                       contacts.subspan(start, count));
    }
}

bool ellipsoids_may_touch(const Ellipsoid& a, const Ellipsoid& b, double reach) {
    // The distance is at least |d| - r_max,A - r_max,B, and at least the gap along the
    // centre line u = d / |d|: -h(-u) = |d| - h_A(u) - h_B(u). Times |d|, the gap test
    // needs no division and its three roots are independent: |d|^2 - h_A(d) - h_B(d) >
    // reach |d|. A negative or NaN reach answers true.
    if (!(reach >= 0.0)) return true;
    const glm::dvec3 d = a.center() - b.center();
    const double d2 = glm::dot(d, d);  // an overflow to infinity is far apart, rightly
    const double spheres = a.bounding_radius() + b.bounding_radius() + reach;
    if (d2 > spheres * spheres) return false;
    if (!(d2 > 0.0)) return true;
    const auto support = [&d](const Ellipsoid& e) {
        const glm::dvec3 scaled = e.sorted_radii() * (d * e.sorted_axes());
        return std::sqrt(glm::dot(scaled, scaled));
    };
    return !(d2 - support(a) - support(b) > reach * std::sqrt(d2));
}

namespace detail {

namespace {

/// The solution as the public call's `solve` finds it, for the tests and the benchmark.
template <class Solve>
PairSolution ordered_solution(const Ellipsoid& a, const Ellipsoid& b, Solve solve) {
    double scale;
    PairFrame frame;
    if (!unit_frame(a, b, scale, frame))
        return {0.0, glm::dvec3(0.0), glm::dvec3(0.0), glm::dvec3(0.0), PairPath::far_field, 0,
                0.0};
    return solve(frame);
}

}  // namespace

bool pair_frame(const Ellipsoid& a, const Ellipsoid& b, PairFrame& frame) {
    const bool swap = key(b) < key(a);
    double scale;
    return unit_frame(swap ? b : a, swap ? a : b, scale, frame);
}

PairSolution pair_solution(const Ellipsoid& a, const Ellipsoid& b) {
    const bool swap = key(b) < key(a);
    return ordered_solution(swap ? b : a, swap ? a : b, cold_solver);
}

PairSolution pair_solution(const Ellipsoid& a, const Ellipsoid& b,
                           const glm::dvec3& previous_normal) {
    const bool swap = key(b) < key(a);
    const Ellipsoid& first = swap ? b : a;
    return ordered_solution(first, swap ? a : b, warm_solver(first, previous_normal, swap));
}

}  // namespace detail

}  // namespace trackphys
