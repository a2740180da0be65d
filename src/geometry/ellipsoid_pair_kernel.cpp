#include "geometry/ellipsoid_pair_kernel.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include <glm/geometric.hpp>

#include "trackphys/math/types.hpp"

// The global minimum of the support function of A - B over the unit sphere
// (docs/ellipsoid_pair.md).
//
// h(n) = d.n + a(n) + b(n) with a(n) = |D_A n| and b(n) = |D_B R^T n| (R = B's axes in A's
// frame) is the support function of the convex body K = A - B: positively homogeneous and
// convex on R^3, with gradient p(n) = d + x_A(n) + x_B(n), the point of K's boundary whose
// outer normal is n (x_A(n) = D_A^2 n / a is A's support point). On the sphere, n is
// critical when p(n) = h(n) n, i.e. the origin lies on K's normal line through p(n), at
// signed depth h(n) below the boundary.
//
// Three facts make the answer certain:
// - Separated (a critical point with h < 0): h is convex on the ball and decreases
//   radially where it is negative, so a local minimum with h < 0 is the minimum over the
//   ball, hence the global one on the sphere (and the only one).
// - Overlapping, shallow (inscribed balls, as in Blaschke's rolling theorem): an ellipsoid
//   holds the ball of radius rho tangent inside at its support point x(n) iff x(n) is the
//   closest boundary point of that ball's centre x(n) - rho n, i.e. (Eberly's largest root
//   of the distance equation, t = -rho a(n) > -r_min^2) iff rho <= r_min^2 / a(n), a(n) the
//   support value. The Minkowski sum of A's such ball and -B's is a ball of radius
//   rho = r_min,A^2 / a(n) + r_min,B^2 / b(n) inside K, tangent to K at p(n). At a critical
//   point with 0 <= h <= rho, the ball of radius h about the origin lies inside that one, so
//   K holds it and no direction has h below: the critical value is the global one.
// - Otherwise, a branch-and-bound search. For unit c and any n, h(n) >= p(c).n (p(c) is a
//   point of K), so on the cap of directions within angle theta of c,
//       h(n) >= (h(c) >= 0 ? cos(theta) h(c) : h(c)) - sin(theta) |p_t(c)|,
//   p_t the part of p(c) orthogonal to c. The cube's faces, cut into squares, cover the
//   sphere; a square whose bound cannot beat the best value found so far is dropped, a
//   square whose centre beats it starts a descent, and the rest are split until the bound
//   is within the search tolerance. The bound is tight to second order in theta, so only
//   the squares about minima as low as the best are split deep.
//
// Descents are Riemannian Newton steps on the sphere with a positive-definite shift where
// the Hessian is not, a trust radius and a backtracking line search, all capped.

namespace trackphys::detail {
namespace {

using glm::dvec3;

/// h, its gradient p and the two support points at a unit direction.
struct Sample {
    dvec3 n;
    double h;
    dvec3 p;   // d + xa + xb
    dvec3 xa;  // A's support point in direction n
    dvec3 xb;  // B's support point in direction n (B's extreme point towards A is -xb)
    double a, b;          // the support values of A and B
    double inv_a, inv_b;  // their inverses
};

/// A descent's end: converged when the last Newton step (with a positive-definite Hessian)
/// was below the step tolerance, i.e. n is a local minimum to rounding.
struct Descent {
    Sample at;
    bool converged;
};

// A descent stops when its Newton step is this short (rad): the value is then exact to
// rounding (the error in h is quadratic in the step) and the direction to ~1e-12.
constexpr double kStepTolerance = 0x1p-40;
// Longest step of a descent (rad): Newton's quadratic model is trusted this far.
constexpr double kTrustRadius = 0.5;
// Newton steps shorter than this (rad), with a positive-definite Hessian, are taken
// without a line search; one shorter than kLastStep is the last (the direction's error after
// a step of length L is about L^2, here ~2^-52 rad).
constexpr double kQuadraticRegion = 0x1p-20;
constexpr double kLastStep = 0x1p-26;
constexpr int kDescentCap = 64;
constexpr int kHalvingCap = 40;
// The search drops a square whose lower bound is within this of the best value (unit
// scale: 2^-37 of the larger semi-axis, 7e-12 of it); the answer is then exact to it.
constexpr double kSearchTolerance = 0x1p-37;
// Squares are not split below this half-size (1e-9 rad), nor is the search run past this
// many evaluations (a near-constant h, as of two equal spheres about one centre, defeats
// any bound; its minimum is then as good as any value).
constexpr double kSmallestHalf = 0x1p-30;
constexpr int kEvaluationCap = 40000;

class PairFunction {
public:
    explicit PairFunction(const PairFrame& frame)
        : ra2_(frame.ra * frame.ra), rb2_(frame.rb * frame.rb), rb_(frame.rb),
          b_axes_(frame.b_axes), d_(frame.d) {}

    int evaluations = 0;

    bool centred() const { return d_ == dvec3(0.0); }

    /// The radius of the ball inside K tangent at p(n): r_min,A^2 / a + r_min,B^2 / b.
    double inscribed(const Sample& s) const { return ra2_.z * s.inv_a + rb2_.z * s.inv_b; }

    Sample at(const dvec3& n) {
        ++evaluations;
        Sample s;
        s.n = n;
        const dvec3 ma = ra2_ * n;
        s.a = std::sqrt(glm::dot(ma, n));
        const dvec3 wb = n * b_axes_;  // B^T n
        const dvec3 scaled_b = rb_ * wb;
        s.b = std::sqrt(glm::dot(scaled_b, scaled_b));
        s.inv_a = 1.0 / s.a;
        s.inv_b = 1.0 / s.b;
        s.xa = ma * s.inv_a;
        s.xb = b_axes_ * (rb2_ * wb) * s.inv_b;
        s.h = glm::dot(d_, n) + s.a + s.b;
        s.p = d_ + s.xa + s.xb;
        return s;
    }

    /// The Hessian of h on the sphere at s in the tangent basis (t1, t2):
    /// t_i^T (H_A + H_B) t_j - h delta_ij, H_A = (D_A^2 - x_A x_A^T) / a, H_B alike.
    std::array<double, 3> tangent_hessian(const Sample& s, const dvec3& t1, const dvec3& t2) const {
        const double a1 = glm::dot(s.xa, t1), a2 = glm::dot(s.xa, t2);
        const dvec3 w1 = t1 * b_axes_, w2 = t2 * b_axes_;
        const double b1 = glm::dot(s.xb, t1), b2 = glm::dot(s.xb, t2);
        const double inv_a = s.inv_a, inv_b = s.inv_b;
        const double h11 = (glm::dot(ra2_ * t1, t1) - a1 * a1) * inv_a +
                           (glm::dot(rb2_ * w1, w1) - b1 * b1) * inv_b - s.h;
        const double h12 = (glm::dot(ra2_ * t1, t2) - a1 * a2) * inv_a +
                           (glm::dot(rb2_ * w1, w2) - b1 * b2) * inv_b;
        const double h22 = (glm::dot(ra2_ * t2, t2) - a2 * a2) * inv_a +
                           (glm::dot(rb2_ * w2, w2) - b2 * b2) * inv_b - s.h;
        return {h11, h12, h22};
    }

private:
    dvec3 ra2_, rb2_, rb_;
    glm::dmat3 b_axes_;
    dvec3 d_;
};

dvec3 unit(const dvec3& v) { return v * (1.0 / std::sqrt(glm::dot(v, v))); }

/// An orthonormal basis (t1, t2) of the plane orthogonal to unit n.
void tangent_basis(const dvec3& n, dvec3& t1, dvec3& t2) {
    const dvec3 m = abs_each(n);
    const dvec3 raw = m.x <= m.y && m.x <= m.z ? dvec3(0.0, n.z, -n.y)
                      : m.y <= m.z             ? dvec3(-n.z, 0.0, n.x)
                                               : dvec3(n.y, -n.x, 0.0);
    t1 = unit(raw);
    t2 = glm::cross(n, t1);
}

Descent descend(PairFunction& f, Sample s) {
    for (int iteration = 0; iteration < kDescentCap; ++iteration) {
        dvec3 t1, t2;
        tangent_basis(s.n, t1, t2);
        const double g1 = glm::dot(t1, s.p), g2 = glm::dot(t2, s.p);
        const auto [h11, h12, h22] = f.tangent_hessian(s, t1, t2);
        // Eigen-decomposition of the 2x2 Hessian: a positive-definite one gives the Newton
        // step; otherwise it is shifted to be positive definite (and at a stationary point
        // that is not a minimum, the step follows the most negative curvature).
        const double mean = 0.5 * (h11 + h22), half_diff = 0.5 * (h11 - h22);
        const double radius = std::sqrt(half_diff * half_diff + h12 * h12);
        const double lowest = mean - radius;
        const double scale = s.a + s.b + std::abs(s.h);
        const bool definite = lowest > 0x1p-30 * scale;
        double s1, s2;
        if (definite) {
            const double det = h11 * h22 - h12 * h12;
            s1 = -(h22 * g1 - h12 * g2) / det;
            s2 = -(h11 * g2 - h12 * g1) / det;
        } else {
            // The shift leaves at least |g| / trust radius of curvature: a flat or concave
            // direction gets a step of about the trust radius (then halved until h
            // decreases), not a crawl along a long flat valley.
            const double shift = std::sqrt(g1 * g1 + g2 * g2) / kTrustRadius - std::min(lowest, 0.0);
            const double k11 = h11 + shift, k22 = h22 + shift;
            const double det = k11 * k22 - h12 * h12;
            s1 = -(k22 * g1 - h12 * g2) / det;
            s2 = -(k11 * g2 - h12 * g1) / det;
            if (std::abs(s1) + std::abs(s2) < kStepTolerance) {
                // The eigenvector of the lowest eigenvalue: (h12, lowest - h11) or its twin.
                double v1 = h12, v2 = lowest - h11;
                if (std::abs(v1) + std::abs(v2) < 0x1p-60 * scale) {
                    v1 = lowest - h22;
                    v2 = h12;
                }
                if (std::abs(v1) + std::abs(v2) < 0x1p-60 * scale) {
                    v1 = 1.0;
                    v2 = 0.0;
                }
                const double norm = std::sqrt(v1 * v1 + v2 * v2);
                s1 = 0.125 * v1 / norm;
                s2 = 0.125 * v2 / norm;
            }
        }
        const double length = std::sqrt(s1 * s1 + s2 * s2);
        if (definite && length < kStepTolerance) return {s, true};
        if (length > kTrustRadius) {
            s1 *= kTrustRadius / length;
            s2 *= kTrustRadius / length;
        }
        // Near a minimum, h cannot tell the last Newton steps apart (it changes by the
        // square of the step, below its rounding once the step is under ~1e-8 rad), while
        // the gradient still can: there the step is taken without the decrease test.
        // Newton's error after a step is about the square of the step, so a step below
        // 2^-26 rad leaves n within ~2^-50 rad of the minimum: it is the last one.
        if (definite && length < kQuadraticRegion) {
            s = f.at(unit(s.n + s1 * t1 + s2 * t2));
            if (length < kLastStep) return {s, true};
            continue;
        }
        bool moved = false;
        for (int halving = 0; halving < kHalvingCap; ++halving) {
            const Sample next = f.at(unit(s.n + s1 * t1 + s2 * t2));
            if (next.h <= s.h) {
                moved = next.n != s.n;
                s = next;
                break;
            }
            s1 *= 0.5;
            s2 *= 0.5;
        }
        // No decrease at all: n is a minimum to rounding (when the Hessian is definite).
        if (!moved) return {s, definite};
    }
    return {s, false};
}

/// A square of a cube face: points q = sign e_axis + u e_(axis+1) + v e_(axis+2) with
/// |u - cu|, |v - cv| <= half, and the lower bound of h over the directions through it.
struct Square {
    double bound;
    double cu, cv, half;
    int axis;
    double sign;
};

dvec3 face_point(int axis, double sign, double u, double v) {
    dvec3 p(0.0);
    p[axis] = sign;
    p[(axis + 1) % 3] = u;
    p[(axis + 2) % 3] = v;
    return p;
}

/// The branch-and-bound search from the best descent so far (see the head of the file),
/// lowest bound first, so that it stops as soon as no square can beat the best value.
Descent search(PairFunction& f, Descent best) {
    std::vector<Square> heap;
    heap.reserve(256);
    const auto later = [](const Square& x, const Square& y) { return x.bound > y.bound; };
    // Evaluates a square: a centre below the best starts a descent; a square that may still
    // hold a lower value is queued.
    const auto visit = [&](double cu, double cv, double half, int axis, double sign) {
        const Sample s = f.at(unit(face_point(axis, sign, cu, cv)));
        if (s.h < best.at.h) {
            const Descent found = descend(f, s);
            if (found.at.h < best.at.h) best = found;
        }
        // Every point of the square is within angle theta of its centre direction, with
        // sin(theta) <= the distance to a corner (sqrt 2 half) over |q| >= 1. K holds the
        // ball of radius rho inscribed at p(c) (see the head of the file), whose support
        // rho + (p(c) - rho c).n bounds h below: the plane bound with h(c) - rho for h(c).
        const double sin_theta = std::min(1.0, 1.4142135623730952 * half);
        const double cos_theta = std::sqrt(1.0 - sin_theta * sin_theta);
        const dvec3 tangential = s.p - glm::dot(s.p, s.n) * s.n;
        const double rho = std::min(f.inscribed(s), std::max(s.h, 0.0));
        const double above = s.h - rho;
        const double bound = rho + (above >= 0.0 ? cos_theta * above : above) -
                             sin_theta * std::sqrt(glm::dot(tangential, tangential));
        if (bound < best.at.h - kSearchTolerance && half >= kSmallestHalf) {
            heap.push_back({bound, cu, cv, half, axis, sign});
            std::push_heap(heap.begin(), heap.end(), later);
        }
    };
    // With both centres at one point h is even, h(-n) = h(n) to the bit, so the faces on
    // one side of the cube cover every value.
    const int sides = f.centred() ? 1 : 2;
    for (int axis = 0; axis < 3; ++axis)
        for (int side = 0; side < sides; ++side)
            for (const double cu : {-0.5, 0.5})
                for (const double cv : {-0.5, 0.5})
                    visit(cu, cv, 0.5, axis, side == 0 ? 1.0 : -1.0);
    while (!heap.empty() && f.evaluations < kEvaluationCap) {
        std::pop_heap(heap.begin(), heap.end(), later);
        const Square q = heap.back();
        heap.pop_back();
        if (q.bound >= best.at.h - kSearchTolerance) break;  // so is every queued square
        const double half = 0.5 * q.half;
        for (const double du : {-half, half})
            for (const double dv : {-half, half}) visit(q.cu + du, q.cv + dv, half, q.axis, q.sign);
    }
    return best;
}

/// Where the minimiser would be if A - B were the ellipsoid E = {x^T M^-1 x <= 1} with
/// M = 2 (M_A + M_B) (A - B itself for two equal spheres): the normal (M + t I)^-1 d at the
/// point of E closest to -d, t >= 0 its Lagrange multiplier, about the distance times E's
/// mean radius s: 0 on the surface (the normal on the centre line), large far away (the
/// centre line itself).
dvec3 first_guess(const PairFrame& frame) {
    // m = M / 2 = D_A^2 + B D_B^2 B^T (symmetric), then (m + t / 2 I)^-1 d by the adjugate
    // (positive definite; its determinant and the scale go with the normalisation).
    const glm::dmat3& b = frame.b_axes;
    const dvec3 rb2 = frame.rb * frame.rb;
    double m[3][3];
    for (int i = 0; i < 3; ++i)
        for (int j = i; j < 3; ++j) {
            m[i][j] = rb2.x * b[0][i] * b[0][j] + rb2.y * b[1][i] * b[1][j] +
                      rb2.z * b[2][i] * b[2][j];
            m[j][i] = m[i][j];
        }
    m[0][0] += frame.ra.x * frame.ra.x;
    m[1][1] += frame.ra.y * frame.ra.y;
    m[2][2] += frame.ra.z * frame.ra.z;
    const dvec3& d = frame.d;
    const double s2 = 2.0 * (m[0][0] + m[1][1] + m[2][2]) / 3.0;  // trace(M) / 3
    const double half_t = std::max(0.0, 0.5 * (std::sqrt(s2 * glm::dot(d, d)) - s2));
    for (int i = 0; i < 3; ++i) m[i][i] += half_t;
    const dvec3 solved(
        (m[1][1] * m[2][2] - m[1][2] * m[1][2]) * d.x + (m[0][2] * m[1][2] - m[0][1] * m[2][2]) * d.y +
            (m[0][1] * m[1][2] - m[0][2] * m[1][1]) * d.z,
        (m[0][2] * m[1][2] - m[0][1] * m[2][2]) * d.x + (m[0][0] * m[2][2] - m[0][2] * m[0][2]) * d.y +
            (m[0][1] * m[0][2] - m[0][0] * m[1][2]) * d.z,
        (m[0][1] * m[1][2] - m[0][2] * m[1][1]) * d.x + (m[0][1] * m[0][2] - m[0][0] * m[1][2]) * d.y +
            (m[0][0] * m[1][1] - m[0][1] * m[0][1]) * d.z);
    const double length2 = glm::dot(solved, solved);
    if (!(length2 > 0x1p-600 && length2 < 0x1p600)) {
        const double d2 = glm::dot(d, d);
        return d2 > 0x1p-600 ? -d * (1.0 / std::sqrt(d2)) : dvec3(0.0, 0.0, 1.0);
    }
    return -solved * (1.0 / std::sqrt(length2));
}

}  // namespace

PairSolution solve_pair(const PairFrame& frame) {
    PairFunction f(frame);
    Descent result = descend(f, f.at(first_guess(frame)));
    PairPath path = PairPath::searched;
    const Sample& at = result.at;
    if (result.converged && at.h < 0.0)
        path = PairPath::separated;
    else if (result.converged && at.h <= f.inscribed(at) + kSearchTolerance)
        path = PairPath::inscribed_balls;
    else
        result = search(f, result);
    return {result.at.h, result.at.n, result.at.xa, -result.at.xb, path, f.evaluations};
}

}  // namespace trackphys::detail
