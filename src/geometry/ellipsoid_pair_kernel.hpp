#pragma once

// The ellipsoid-ellipsoid contact in the first ellipsoid's sorted frame at unit scale
// (internal; the public entry is ellipsoid_pair.hpp). Exposed for the tests and the
// benchmark, which check which path answered.

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include "trackphys/geometry/ellipsoid.hpp"

namespace trackphys::detail {

/// How the global minimum was established.
enum class PairPath {
    separated,        ///< a local minimum below zero: h is convex there, so it is the only one
    inscribed_balls,  ///< a critical point no deeper than the balls inscribed at its support points
    searched,         ///< the branch-and-bound search over the sphere of directions
    /// the search stopped at its evaluation cap (or at its smallest squares) with squares
    /// whose bounds are below the best value: the lowest value its descents found, not
    /// proven the global minimum (lower_bound says how far below it could be)
    unproven,
    far_field,  ///< centres too far apart for the solver: the closed form along them
};

/// A pair seen from A's sorted frame, lengths divided by a power of two so that the
/// largest semi-axis of the two lies in [1, 2).
struct PairFrame {
    glm::dvec3 ra;      ///< A's radii, sorted descending
    glm::dvec3 rb;      ///< B's radii, sorted descending
    glm::dmat3 b_axes;  ///< B's sorted axes in A's frame (columns, a rotation)
    glm::dvec3 d;       ///< cA - cB in A's frame
    glm::dvec3 d_in_b;  ///< cA - cB in B's sorted frame (straight from world space)
};

struct PairSolution {
    double depth;          ///< min over unit n of h(n), at the frame's scale
    glm::dvec3 n;          ///< the unit minimiser (from A towards B); normal = -n
    glm::dvec3 extreme_a;  ///< A's support point in direction n, relative to cA
    glm::dvec3 extreme_b;  ///< B's support point in direction -n, relative to cB
    PairPath path;
    int evaluations;  ///< evaluations of h over every descent and the search
    /// A proven lower bound of the minimum: depth itself for a certified critical point,
    /// depth less the search's tolerance (2^-37 at unit scale) for a finished search, the
    /// lowest bound left unresolved for an unproven one.
    double lower_bound;
};

/// The global minimum of h. Radii must be finite, sorted, >= 2^-200 and <= 2; d finite
/// with every component below 2^500 in magnitude.
PairSolution solve_pair(const PairFrame& frame);

/// The same minimum with the first descent started at `start` (a direction, |start| within
/// 2^-30..2^30) instead of the first guess: a descent certified by either certificate is
/// the answer; otherwise solve_pair(frame)'s, bit for bit, with the warm descent's
/// evaluations counted too.
PairSolution solve_pair(const PairFrame& frame, const glm::dvec3& start);

/// How ellipsoid_ellipsoid_contact(a, b) establishes its answer, and how many evaluations
/// of h it takes (for the tests and the benchmark).
PairSolution pair_solution(const Ellipsoid& a, const Ellipsoid& b);

/// How ellipsoid_ellipsoid_contact(a, b, previous_normal) establishes its answer.
PairSolution pair_solution(const Ellipsoid& a, const Ellipsoid& b,
                           const glm::dvec3& previous_normal);

}  // namespace trackphys::detail
