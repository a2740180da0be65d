#pragma once

// The ellipsoid-ellipsoid contact in the first ellipsoid's sorted frame at unit scale
// (internal; the public entry is ellipsoid_pair.hpp). Exposed for the tests and the
// benchmark, which check which path answered.

#include <span>

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include "trackphys/geometry/ellipsoid.hpp"

namespace trackphys::detail {

// The descent's tolerances, shared by solve_pair and its lanes (ellipsoid_pair_lanes.hpp).
// A descent stops when its Newton step is this short (rad): the value is then exact to
// rounding (the error in h is quadratic in the step) and the direction to ~1e-12.
constexpr double kStepTolerance = 0x1p-40;
// Longest step of a descent (rad): Newton's quadratic model is trusted this far.
constexpr double kTrustRadius = 0.5;
// Newton steps shorter than this (rad), with a positive-definite Hessian, are taken
// without a line search. Newton's error after a step of length L is about K L^2, K
// estimated from the step before as L / L_prev^2: a step that leaves it below
// kDirectionTolerance, or is itself shorter than kLastStep (~2^-52 rad after it even with no
// estimate), is the last, and the descent ends at its second-order model
// (PairFunction::stepped) without evaluating h there.
constexpr double kQuadraticRegion = 0x1p-20;
constexpr double kDirectionTolerance = 0x1p-40;
constexpr double kLastStep = 0x1p-26;
constexpr int kDescentCap = 64;
// The search drops a square whose lower bound is within this of the best value (unit
// scale: 2^-37 of the larger semi-axis, 7e-12 of it); the answer is then exact to it.
constexpr double kSearchTolerance = 0x1p-37;

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

/// The frame ellipsoid_ellipsoid_contact(a, b) solves in, or false for a far-field pair.
bool pair_frame(const Ellipsoid& a, const Ellipsoid& b, PairFrame& frame);

/// How ellipsoid_ellipsoid_contact(a, b) establishes its answer, and how many evaluations
/// of h it takes (for the tests and the benchmark).
PairSolution pair_solution(const Ellipsoid& a, const Ellipsoid& b);

/// How ellipsoid_ellipsoid_contact(a, b, previous_normal) establishes its answer.
PairSolution pair_solution(const Ellipsoid& a, const Ellipsoid& b,
                           const glm::dvec3& previous_normal);

/// solve_pair's common path for many frames at once (ellipsoid_pair_lanes.hpp): the first
/// guess, definite Newton steps that decrease h, the quadratic-region stop and the separated
/// or inscribed-balls certificate, four frames at a time in AVX2 lanes where use_four_lanes(),
/// two otherwise. kept[i] says whether frames[i] stayed on that path: then solutions[i] is
/// solve_pair(frames[i]) bit for bit; else (and for a lone last frame, which the lanes would
/// take longer over than solve_pair) solutions[i] is unset and the caller solves it.
/// The three spans have one size.
void solve_pairs_on_common_path(std::span<const PairFrame> frames,
                                std::span<PairSolution> solutions, std::span<bool> kept);

}  // namespace trackphys::detail
