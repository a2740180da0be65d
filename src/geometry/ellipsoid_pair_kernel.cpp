#include "geometry/ellipsoid_pair_kernel.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
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
// - Otherwise, descents from both ellipsoids' axes, then a branch-and-bound search. For
//   unit c and any n, h(n) >= p(c).n (p(c) is a point of K), so on the cap of directions
//   within angle theta of c,
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
    dvec3 p;              // d + xa + xb
    dvec3 xa;             // A's support point in direction n
    dvec3 xb;             // B's support point in direction n (B's extreme point towards A is -xb)
    double a, b;          // the support values of A and B
    double inv_a, inv_b;  // their inverses
};

/// A symmetric 2x2 form in a tangent basis.
struct Curvature {
    double k11, k12, k22;
};

/// A descent's end: converged when the last Newton step (with a positive-definite Hessian)
/// was below the step tolerance, i.e. n is a local minimum to rounding.
struct Descent {
    Sample at;
    bool converged;
};

constexpr int kHalvingCap = 40;
// Squares are not split below this half-size (1e-9 rad), nor is the search run past this
// many evaluations (a near-constant h, as of two equal spheres about one centre, defeats
// any bound; its minimum is then as good as any value). A needle's valley reaches it too,
// uncertified: the descents from the axes (from_axes) run first to land in that valley,
// and solve_pair reports the answer as PairPath::unproven with the bound left unresolved.
constexpr double kSmallestHalf = 0x1p-30;
constexpr int kEvaluationCap = 40000;

dvec3 unit(const dvec3& v) { return v * (1.0 / std::sqrt(glm::dot(v, v))); }

/// An orthonormal basis (t1, t2) of the plane orthogonal to unit n. Forced inline: every
/// descent step takes one, and with the search's callers the compiler would make it a call.
[[gnu::always_inline]] inline void tangent_basis(const dvec3& n, dvec3& t1, dvec3& t2) {
    const dvec3 m = abs_each(n);
    const dvec3 raw = m.x <= m.y && m.x <= m.z ? dvec3(0.0, n.z, -n.y)
                      : m.y <= m.z             ? dvec3(-n.z, 0.0, n.x)
                                               : dvec3(n.y, -n.x, 0.0);
    t1 = unit(raw);
    t2 = glm::cross(n, t1);
}

class PairFunction {
  public:
    explicit PairFunction(const PairFrame& frame)
        : ra2_(frame.ra * frame.ra),
          rb2_(frame.rb * frame.rb),
          rb_(frame.rb),
          cofactor_a_(cofactor(frame.ra)),
          cofactor_b_(cofactor(frame.rb)),
          largest_a_(frame.ra.x),
          b_axes_(frame.b_axes),
          d_(frame.d),
          mb_(support_matrix(frame.b_axes, rb2_)) {}

    int evaluations = 0;

    bool centred() const { return d_ == dvec3(0.0); }

    /// The radius of the ball inside K tangent at p(n): r_min,A^2 / a + r_min,B^2 / b.
    double inscribed(const Sample& s) const { return ra2_.z * s.inv_a + rb2_.z * s.inv_b; }

    // Lane twin: PairLanes::at (ellipsoid_pair_lanes.hpp), the same operations
    // in the same order; the EllipsoidPairBatch tests fail when they differ.
    /// The sample at the direction of m (|m| within 2^-30..2^30: with radii of 2^-200..2,
    /// l^2 A^2 B^2 below stays a normal number).
    /// One division serves the three inverses: with l = |m|, A = a(m) and B = b(m),
    /// q = 1 / (l A B) gives 1 / l = A B q, 1 / a(n) = l / A = l^2 B q and 1 / b(n) alike.
    /// It divides by the product of the squares, so that it runs beside the roots rather
    /// than after them: q = l A B / (l^2 A^2 B^2).
    Sample at(const dvec3& m) {
        ++evaluations;
        Sample s;
        const double l2 = glm::dot(m, m);
        const dvec3 ma = ra2_ * m;
        const double a2 = glm::dot(ma, m);
        const dvec3 wb = m * b_axes_;  // B^T m
        const dvec3 scaled_b = rb_ * wb;
        const double b2 = glm::dot(scaled_b, scaled_b);
        const double inverse_square = 1.0 / (l2 * a2 * b2);
        const double l = std::sqrt(l2), big_a = std::sqrt(a2), big_b = std::sqrt(b2);
        const double q = l * big_a * big_b * inverse_square;
        const double inv_l = big_a * big_b * q;
        const double l2q = l * l * q;
        s.n = m * inv_l;
        s.a = big_a * inv_l;
        s.b = big_b * inv_l;
        s.inv_a = l2q * big_b;
        s.inv_b = l2q * big_a;
        // x_A(n) = D_A^2 n / a(n) = D_A^2 m / A, x_B alike.
        const double inv_big_a = l * big_b * q, inv_big_b = l * big_a * q;
        s.xa = ma * inv_big_a;
        s.xb = b_axes_ * (rb2_ * wb) * inv_big_b;
        s.h = glm::dot(d_, s.n) + s.a + s.b;
        s.p = d_ + s.xa + s.xb;
        return s;
    }

    // Lane twin: PairLanes::definite_step (ellipsoid_pair_lanes.hpp), the same operations
    // in the same order; the EllipsoidPairBatch tests fail when they differ.
    /// The Newton step on the sphere at s, when the Hessian there is positive definite with
    /// its least eigenvalue above `floor`: false otherwise. No tangent basis: the Hessian of
    /// h on R^3, H = (D_A^2 - x_A x_A^T) / a + (M_B - x_B x_B^T) / b, has n in its kernel,
    /// so S = H - h I + (h + a + b) n n^T is the Riemannian Hessian on the plane orthogonal
    /// to n and a + b along n, and S step = -(p - h n) has the tangent Newton step as its
    /// solution. The tangent eigenvalues sum to trace S - (a + b) and multiply to
    /// det S / (a + b); both above floor, with their product above floor (sum - floor),
    /// says the least one is. `next` is n + step times det S (> 0), n det S - adj(S) g,
    /// when that stays in the evaluation's range: the evaluation normalises its argument,
    /// so it need not wait for the division by det S.
    bool definite_step(const Sample& s, double floor, dvec3& step, dvec3& next) const {
        const dvec3 fa = s.xa * s.inv_a, fb = s.xb * s.inv_b;
        const double along = s.h + s.a + s.b;
        const dvec3 fn = s.n * along;
        const double s00 = (ra2_.x * s.inv_a - s.h) + mb_[0] * s.inv_b - fa.x * s.xa.x -
                           fb.x * s.xb.x + fn.x * s.n.x;
        const double s11 = (ra2_.y * s.inv_a - s.h) + mb_[1] * s.inv_b - fa.y * s.xa.y -
                           fb.y * s.xb.y + fn.y * s.n.y;
        const double s22 = (ra2_.z * s.inv_a - s.h) + mb_[2] * s.inv_b - fa.z * s.xa.z -
                           fb.z * s.xb.z + fn.z * s.n.z;
        const double s01 = mb_[3] * s.inv_b - fa.x * s.xa.y - fb.x * s.xb.y + fn.x * s.n.y;
        const double s02 = mb_[4] * s.inv_b - fa.x * s.xa.z - fb.x * s.xb.z + fn.x * s.n.z;
        const double s12 = mb_[5] * s.inv_b - fa.y * s.xa.z - fb.y * s.xb.z + fn.y * s.n.z;
        const double c00 = s11 * s22 - s12 * s12, c01 = s02 * s12 - s01 * s22,
                     c02 = s01 * s12 - s02 * s11, c11 = s00 * s22 - s02 * s02,
                     c12 = s01 * s02 - s00 * s12, c22 = s00 * s11 - s01 * s01;
        const double det = s00 * c00 + s01 * c01 + s02 * c02;
        const double normal_part = s.a + s.b;
        const double sum = s00 + s11 + s22 - normal_part;
        if (!(sum > 2.0 * floor && det > normal_part * floor * (sum - floor))) return false;
        const dvec3 g = s.p - s.h * s.n;
        const double scale = -1.0 / det;
        const dvec3 solved(c00 * g.x + c01 * g.y + c02 * g.z, c01 * g.x + c11 * g.y + c12 * g.z,
                           c02 * g.x + c12 * g.y + c22 * g.z);
        step = solved * scale;
        // |n + step| <= 1.2 within the trust radius: 2^-29..2^29 keeps |next| within 2^-30..2^30.
        next = det >= 0x1p-29 && det <= 0x1p29 ? s.n * det - solved : s.n + step;
        return true;
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

    /// A lower bound K of the curvature of h (the convex function on R^3) across the plane
    /// m = s.n + y, y = y1 t1 + y2 t2 orthogonal to s.n, |y| <= tau: y^T K y <= y^T Hess h(m) y
    /// at every such m. For a(m) = |D m| and unit t in the plane,
    ///     t^T Hess a(m) t = |D m x D t|^2 / |D m|^3 = |C (m x t)|^2 / |D m|^3,
    /// C = cof D = diag(r2 r3, r1 r3, r1 r2); m x t = u + beta n with u = n x t a unit vector
    /// of the plane and |beta| <= tau, so |C (m x t)|^2 >= |C u|^2 - 2 tau |C u . C n|; also
    /// |D m| <= a(n) + r1 tau. For B, C = cof(D_B) R^T. Exact at tau = 0.
    Curvature curvature_floor(const Sample& s, const dvec3& t1, const dvec3& t2, double tau) const {
        // n x t1 = t2 and n x t2 = -t1: the form in t is the form in n x t, turned.
        Curvature k{0.0, 0.0, 0.0};
        double loss = 0.0;
        const auto add = [&](const dvec3& c1, const dvec3& c2, const dvec3& cn, double value,
                             double largest) {
            const double reach = (value + largest * tau) * (1.0 + 0x1p-46);
            const double weight = 1.0 / (reach * reach * reach);
            const double p11 = glm::dot(c1, c1), p12 = glm::dot(c1, c2), p22 = glm::dot(c2, c2);
            k.k11 += weight * p22;
            k.k12 -= weight * p12;
            k.k22 += weight * p11;
            // 2 tau max |C u . C n| over unit u in the plane.
            const double q1 = glm::dot(c1, cn), q2 = glm::dot(c2, cn);
            loss += 2.0 * tau * std::sqrt(q1 * q1 + q2 * q2) * weight;
        };
        add(cofactor_a_ * t1, cofactor_a_ * t2, cofactor_a_ * s.n, s.a, largest_a_);
        add(cofactor_b_ * (t1 * b_axes_), cofactor_b_ * (t2 * b_axes_),
            cofactor_b_ * (s.n * b_axes_), s.b, rb_.x);
        // The rounding of the sums is below 2^-50 of their scale; the margin covers it.
        const double margin = loss * (1.0 + 0x1p-46) + 0x1p-46 * (k.k11 + k.k22);
        k.k11 -= margin;
        k.k22 -= margin;
        return k;
    }

    // Lane twin: PairLanes::stepped (ellipsoid_pair_lanes.hpp), the same operations
    // in the same order; the EllipsoidPairBatch tests fail when they differ.
    /// The sample at n + step for a Newton step short enough (below 2^-20 rad) that its
    /// second-order model is exact to rounding: h by the model's minimum h + g.step / 2
    /// (g = p - h n, and Hess step = -g; its error is the third order, ~2^-60), the support
    /// points by their first-order change x + Hess_A step, the support values by a + x_A.step
    /// (both within ~|step|^2 of the rest of the scale). Saves an evaluation's three roots
    /// and its division at the end of each descent.
    Sample stepped(const Sample& s, const dvec3& step) const {
        Sample t;
        const dvec3 m = s.n + step;
        // |m|^2 = 1 + |step|^2 to within 2^-40: one Newton step of 1 / sqrt from 1 is exact.
        t.n = m * (1.5 - 0.5 * glm::dot(m, m));
        const double da = glm::dot(s.xa, step), db = glm::dot(s.xb, step);
        t.xa = s.xa + (ra2_ * step - s.xa * da) * s.inv_a;
        t.xb = s.xb + (mb(step) - s.xb * db) * s.inv_b;
        t.a = s.a + da;
        t.b = s.b + db;
        t.inv_a = s.inv_a * (1.0 - da * s.inv_a);
        t.inv_b = s.inv_b * (1.0 - db * s.inv_b);
        t.h = s.h + 0.5 * glm::dot(s.p - s.h * s.n, step);
        t.p = d_ + t.xa + t.xb;
        return t;
    }

    /// B's support matrix M_B = R D_B^2 R^T in A's frame: xx, yy, zz, xy, xz, yz.
    const std::array<double, 6>& support_matrix_b() const { return mb_; }

  private:
    dvec3 mb(const dvec3& v) const {
        return {mb_[0] * v.x + mb_[3] * v.y + mb_[4] * v.z,
                mb_[3] * v.x + mb_[1] * v.y + mb_[5] * v.z,
                mb_[4] * v.x + mb_[5] * v.y + mb_[2] * v.z};
    }

    static dvec3 cofactor(const dvec3& r) { return {r.y * r.z, r.x * r.z, r.x * r.y}; }

    // Lane twin: PairLanes' constructor (ellipsoid_pair_lanes.hpp), the same operations
    // in the same order; the EllipsoidPairBatch tests fail when they differ.
    static std::array<double, 6> support_matrix(const glm::dmat3& axes, const dvec3& r2) {
        const auto entry = [&](int i, int j) {
            return r2.x * axes[0][i] * axes[0][j] + r2.y * axes[1][i] * axes[1][j] +
                   r2.z * axes[2][i] * axes[2][j];
        };
        return {entry(0, 0), entry(1, 1), entry(2, 2), entry(0, 1), entry(0, 2), entry(1, 2)};
    }

    dvec3 ra2_, rb2_, rb_;
    dvec3 cofactor_a_, cofactor_b_;
    double largest_a_;
    glm::dmat3 b_axes_;
    dvec3 d_;
    std::array<double, 6> mb_;
};

/// The step where the Hessian on the sphere is not safely positive definite, in a tangent
/// basis: shifted until its lowest eigenvalue is |gradient| / the trust radius, so that a flat
/// or concave direction gets a step of about the trust radius (then halved until h
/// decreases) rather than a crawl along a long flat valley; at a stationary point that is not
/// a minimum, along the most negative curvature.
dvec3 shifted_step(const PairFunction& f, const Sample& s) {
    dvec3 t1, t2;
    tangent_basis(s.n, t1, t2);
    const double g1 = glm::dot(t1, s.p), g2 = glm::dot(t2, s.p);
    const auto [h11, h12, h22] = f.tangent_hessian(s, t1, t2);
    const double mean = 0.5 * (h11 + h22), half_diff = 0.5 * (h11 - h22);
    const double lowest = mean - std::sqrt(half_diff * half_diff + h12 * h12);
    const double shift = std::sqrt(g1 * g1 + g2 * g2) / kTrustRadius - std::min(lowest, 0.0);
    const double k11 = h11 + shift, k22 = h22 + shift;
    const double det = k11 * k22 - h12 * h12;
    double s1 = -(k22 * g1 - h12 * g2) / det;
    double s2 = -(k11 * g2 - h12 * g1) / det;
    if (std::abs(s1) + std::abs(s2) < kStepTolerance) {
        // The eigenvector of the lowest eigenvalue: (h12, lowest - h11) or its twin.
        const double scale = s.a + s.b + std::abs(s.h);
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
    return s1 * t1 + s2 * t2;
}

// Lane twin: PairLanes::solve's loop (ellipsoid_pair_lanes.hpp), the same operations
// in the same order; the EllipsoidPairBatch tests fail when they differ.
/// The start is taken by reference: passed by value, the caller's copy into the argument
/// reloads the sample it has just stored with loads that straddle those stores, and waits.
Descent descend(PairFunction& f, const Sample& start) {
    Sample s = start;
    // Lengths are compared squared: the next evaluation need not wait for the step's root.
    double previous2 = 0.0;  // the last step's squared length, 0 before the first
    for (int iteration = 0; iteration < kDescentCap; ++iteration) {
        // A positive-definite Hessian gives the Newton step; otherwise it is shifted.
        const double scale = s.a + s.b + std::abs(s.h);
        // next: a positive multiple of s.n + step, for the evaluation there.
        dvec3 step, next;
        const bool definite = f.definite_step(s, 0x1p-30 * scale, step, next);
        if (!definite) {
            step = shifted_step(f, s);
            next = s.n + step;
        }
        double length2 = glm::dot(step, step);
        if (definite && length2 < kStepTolerance * kStepTolerance) return {s, true};
        if (length2 > kTrustRadius * kTrustRadius) {
            step *= kTrustRadius / std::sqrt(length2);
            length2 = kTrustRadius * kTrustRadius;
            next = s.n + step;
        }
        // Near a minimum, h cannot tell the last Newton steps apart (it changes by the
        // square of the step, below its rounding once the step is under ~1e-8 rad), while
        // the gradient still can: there the step is taken without the decrease test.
        if (definite && length2 < kQuadraticRegion * kQuadraticRegion) {
            // L^3 <= tolerance L_prev^2, squared.
            if (length2 < kLastStep * kLastStep ||
                length2 * length2 * length2 <=
                    kDirectionTolerance * kDirectionTolerance * previous2 * previous2)
                return {f.stepped(s, step), true};
            s = f.at(next);
            previous2 = length2;
            continue;
        }
        bool moved = false;
        previous2 = length2;
        for (int halving = 0; halving < kHalvingCap; ++halving) {
            const Sample trial = f.at(next);
            if (trial.h <= s.h) {
                moved = trial.n != s.n;
                s = trial;
                break;
            }
            step *= 0.5;
            next = s.n + step;
            previous2 *= 0.25;
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

/// A lower bound of h over the directions within angle atan(tau) of s.n that loses only
/// the third order at a minimiser, where the ball's bound loses (h - rho) theta^2 / 2 (and
/// would split the squares about it down to ~2^-18 rad). On the plane through c = s.n,
/// g(y) = h(c + y) (y orthogonal to c, r = |y| <= tau) is convex with Hessian >= K
/// (curvature_floor), so with G = (p.t1, p.t2) the gradient,
///     g(y) >= N(y) = h(c) + G.y + y^T K y / 2,
/// and h((c + y) / |c + y|) = g / sqrt(1 + r^2) >= N - max(N, 0) r^2 / 2
///     >= h(c) + G.y + y^T W y / 2,  W = K - (max(h, 0) + |G| tau + max(l_max(K), 0) tau^2 / 2) I.
/// When W is positive definite the least value over the plane, h - G^T W^-1 G / 2, bounds the
/// disc; with nu the least eigenvalue of W, so does the least of h - |G| r + nu r^2 / 2 over
/// r in [0, tau].
double curved_bound(const PairFunction& f, const Sample& s, double tau) {
    dvec3 t1, t2;
    tangent_basis(s.n, t1, t2);
    const double g1 = glm::dot(s.p, t1), g2 = glm::dot(s.p, t2);
    const double slope = std::sqrt(g1 * g1 + g2 * g2);
    const Curvature k = f.curvature_floor(s, t1, t2, tau);
    const auto eigen = [](double m11, double m12, double m22, double sign) {
        const double half_diff = 0.5 * (m11 - m22);
        return 0.5 * (m11 + m22) + sign * std::sqrt(half_diff * half_diff + m12 * m12);
    };
    const double shift = std::max(s.h, 0.0) + slope * tau +
                         0.5 * std::max(eigen(k.k11, k.k12, k.k22, 1.0), 0.0) * tau * tau;
    const double w11 = k.k11 - shift, w22 = k.k22 - shift;
    const double highest = eigen(w11, k.k12, w22, 1.0);
    // The eigenvalue's rounding is below 2^-50 of the largest one; the margin covers it.
    const double nu = eigen(w11, k.k12, w22, -1.0) - 0x1p-46 * std::abs(highest);
    const double at_edge = s.h - slope * tau + 0.5 * nu * tau * tau;
    double bound = std::min(at_edge, s.h);  // a NaN edge stays NaN
    if (nu > 0.0) {
        // G^T adj(W) G / det(W), the numerator raised by its rounding, det(W) = nu highest.
        const double adjugate = w22 * g1 * g1 - 2.0 * k.k12 * g1 * g2 + w11 * g2 * g2 +
                                0x1p-46 * highest * slope * slope;
        const double plane = s.h - 0.5 * adjugate / (nu * highest);
        bound = slope > nu * tau ? std::max(plane, at_edge) : plane;
    }
    // Every such bound is at most h(c); a NaN (from extreme radii overflowing) bounds nothing.
    return bound <= s.h ? bound : -std::numeric_limits<double>::infinity();
}

/// A cap of directions about a sample's where h is certified no lower than a floor:
/// cos of its angular radius, above 1 when none is.
struct Cap {
    dvec3 centre;
    double cos_radius;

    /// Whether the cap holds every direction within angle theta of unit c.
    bool holds(const dvec3& c, double sin_theta, double cos_theta) const {
        const double cos_phi = glm::dot(c, centre);
        if (!(cos_phi > cos_radius)) return false;  // c itself is outside
        const double sin_phi = glm::length(glm::cross(c, centre));
        return cos_phi * cos_theta - sin_phi * sin_theta >= cos_radius + 0x1p-44;
    }
};

/// The widest cap about s (of radius atan(tau), tau = 2^-2 .. 2^-12) whose curved bound
/// reaches the floor. About a minimiser the curved bound is h there, less rounding, as long
/// as the curvature floor exceeds h: a cap of about its least eigenvalue over the rate at
/// which the floor falls, which drops the squares about the minimiser a few levels down
/// instead of splitting them until the ball's bound is within tolerance.
Cap certified_cap(const PairFunction& f, const Sample& s, double floor) {
    for (double tau = 0x1p-2; tau >= 0x1p-12; tau *= 0.7071067811865476)
        if (curved_bound(f, s, tau) >= floor)
            return {s.n, (1.0 + 0x1p-46) / std::sqrt(1.0 + tau * tau)};
    return {s.n, 2.0};
}

/// The branch-and-bound search from the best descent so far (see the head of the file),
/// lowest bound first, so that it stops as soon as no square can beat the best value.
Descent search(PairFunction& f, Descent best, double& unresolved) {
    std::vector<Square> heap;
    heap.reserve(256);
    const auto later = [](const Square& x, const Square& y) { return x.bound > y.bound; };
    // Evaluates a square: a centre below the best starts a descent; a square that may still
    // hold a lower value is queued.
    // The best minimiser's certified cap (and, when h is even, its antipode's) drops the
    // squares inside it unseen.
    const bool even = f.centred();
    Cap cap = certified_cap(f, best.at, best.at.h - kSearchTolerance);
    const auto visit = [&](double cu, double cv, double half, int axis, double sign) {
        const dvec3 q = face_point(axis, sign, cu, cv);
        const double inv_length = 1.0 / std::sqrt(glm::dot(q, q));
        const dvec3 c = q * inv_length;
        // Every point x of the square is within angle theta < pi/2 of its centre direction
        // c = q / |q|, with sin(theta) <= |x - q| / |q| <= sqrt 2 half / |q| (the law of
        // sines in the triangle 0, q, x). K holds the ball of radius rho inscribed at p(c)
        // (see the head of the file), whose support rho + (p(c) - rho c).n bounds h below:
        // the plane bound with h(c) - rho for h(c).
        const double sin_theta = 1.4142135623730952 * half * inv_length * (1.0 + 0x1p-46);
        const double cos_theta = std::sqrt(1.0 - sin_theta * sin_theta);
        if (cap.holds(c, sin_theta, cos_theta) || (even && cap.holds(-c, sin_theta, cos_theta)))
            return;
        const Sample s = f.at(c);
        if (s.h < best.at.h) {
            const Descent found = descend(f, s);
            if (found.at.h < best.at.h) {
                best = found;
                cap = certified_cap(f, best.at, best.at.h - kSearchTolerance);
            }
        }
        const dvec3 tangential = s.p - glm::dot(s.p, s.n) * s.n;
        const double slope = std::sqrt(glm::dot(tangential, tangential));
        const double rho = std::min(f.inscribed(s), std::max(s.h, 0.0));
        const double above = s.h - rho;
        double bound = rho + (above >= 0.0 ? cos_theta * above : above) - sin_theta * slope;
        // The curved bound is at most h(c): no use below the best.
        if (bound < best.at.h - kSearchTolerance && s.h >= best.at.h - kSearchTolerance &&
            half >= kSmallestHalf) {
            const double curved = curved_bound(f, s, sin_theta / cos_theta * (1.0 + 0x1p-46));
            if (curved > bound) bound = curved;  // never a NaN
        }
        if (bound < best.at.h - kSearchTolerance) {
            if (half >= kSmallestHalf) {
                heap.push_back({bound, cu, cv, half, axis, sign});
                std::push_heap(heap.begin(), heap.end(), later);
            } else {
                unresolved = std::min(unresolved, bound);
            }
        }
    };
    // With both centres at one point h is even, h(-n) = h(n) to the bit, so the faces on
    // one side of the cube cover every value.
    const int sides = even ? 1 : 2;
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
    // Stopped by the cap: the queued squares' bounds are all that is known below the best.
    if (!heap.empty()) unresolved = std::min(unresolved, heap.front().bound);
    return best;
}

// Lane twin: PairLanes::first_guess (ellipsoid_pair_lanes.hpp), the same operations
// in the same order; the EllipsoidPairBatch tests fail when they differ.
/// Where the minimiser would be if a, b and h kept their values at the centre line
/// u = -d / |d|: the minimiser solves (M_A / a + M_B / b - h I) n = -d (the critical point
/// condition p = h n), so with a(u), b(u) and h(u) frozen, n is that system's solution.
/// Exact for two spheres; closer than a model ellipsoid of A - B with fixed weights, such
/// as 2 (M_A + M_B), because the weights 1 / a and 1 / b follow the two shapes along u.
/// h is capped at half the radius of the balls inscribed at u, r_min,A^2 / a + r_min,B^2 / b,
/// which keeps the matrix positive definite (its least eigenvalue is at least that radius)
/// where a deep centre line would turn it. Not normalised (the evaluation does that): its
/// length is kept when within 2^-30..2^30 (the evaluation's range), else brought within
/// 2^-4..2^4 by a power of two, without a root or a division on the way.
dvec3 first_guess(const PairFrame& frame, const std::array<double, 6>& mb) {
    // Times a(u) b(u) |d| (a positive scale, which the normalisation removes): with
    // D2 = |d|^2, A = |D_A d| = a(u) |d| and B = b(u) |d|, the system's matrix is
    // D2 (B M_A + A M_B) - A B (A + B - D2) I and the cap on h is D2 (r_min,A^2 B +
    // r_min,B^2 A) / 2: two independent roots and no division. B comes from d in B's own
    // frame, so that its root need not wait for M_B.
    const dvec3 ra2 = frame.ra * frame.ra, rb2 = frame.rb * frame.rb;
    const dvec3& d = frame.d;
    const double d2 = glm::dot(d, d);
    const double big_a = std::sqrt(glm::dot(ra2 * d, d));
    const double big_b = std::sqrt(glm::dot(rb2 * frame.d_in_b, frame.d_in_b));
    const double shift =
        std::min(big_a * big_b * (big_a + big_b - d2), 0.5 * d2 * (ra2.z * big_b + rb2.z * big_a));
    const double wa = d2 * big_b, wb = d2 * big_a;
    const double m00 = wa * ra2.x + wb * mb[0] - shift, m11 = wa * ra2.y + wb * mb[1] - shift,
                 m22 = wa * ra2.z + wb * mb[2] - shift;
    const double m01 = wb * mb[3], m02 = wb * mb[4], m12 = wb * mb[5];
    const double c00 = m11 * m22 - m12 * m12, c01 = m02 * m12 - m01 * m22,
                 c02 = m01 * m12 - m02 * m11, c11 = m00 * m22 - m02 * m02,
                 c12 = m01 * m02 - m00 * m12, c22 = m00 * m11 - m01 * m01;
    const dvec3 solved(c00 * d.x + c01 * d.y + c02 * d.z, c01 * d.x + c11 * d.y + c12 * d.z,
                       c02 * d.x + c12 * d.y + c22 * d.z);
    const double length2 = glm::dot(solved, solved);
    // Within the evaluation's range as it is (the usual case): the evaluation's result does
    // not change when m is scaled by a power of two, so the exponent work below is skipped
    // and the guess's length need not be on the way to the first evaluation.
    if (length2 >= 0x1p-60 && length2 <= 0x1p60) return -solved;
    if (!(length2 > 0x1p-600 && length2 < 0x1p600))
        return d2 > 0x1p-600 ? -d * (1.0 / std::sqrt(d2)) : dvec3(0.0, 0.0, 1.0);
    // 2^-e for length2 in [2^2e, 2^(2e+2)): the exponent of length2, halved and negated.
    const auto exponent = int((std::bit_cast<std::uint64_t>(length2) >> 52) & 0x7ff) - 1023;
    const double scale =
        std::bit_cast<double>(std::uint64_t(1023 - (exponent >> 1)) << 52);  // exact
    return -solved * scale;
}

/// The lowest of best and the descents from both ellipsoids' axes (one way when h is even).
/// An elongated shape's minima lie in a valley about the great circle orthogonal to its long
/// axis, r_min / r_max rad wide (3.5e-5 for a 1e4:1 needle), which its shorter axes lie on:
/// the search's squares resolve such a valley only below that size, all along the circle,
/// which takes more than its evaluation cap; a descent from an axis lands in it at once.
Descent from_axes(PairFunction& f, Descent best, const PairFrame& frame) {
    const int sides = f.centred() ? 1 : 2;
    for (int body = 0; body < 2; ++body)
        for (int i = 0; i < 3; ++i)
            for (int side = 0; side < sides; ++side) {
                dvec3 axis = body == 0 ? dvec3(0.0) : frame.b_axes[i];
                if (body == 0) axis[i] = 1.0;
                const Descent found = descend(f, f.at(side == 0 ? axis : -axis));
                if (found.at.h < best.at.h) best = found;
            }
    return best;
}

/// Which certificate makes a descent's end the global minimum: separated or
/// inscribed_balls, or searched when neither holds.
PairPath certificate(const PairFunction& f, const Descent& result) {
    const Sample& at = result.at;
    if (result.converged && at.h < 0.0) return PairPath::separated;
    if (result.converged && at.h <= f.inscribed(at) + kSearchTolerance)
        return PairPath::inscribed_balls;
    return PairPath::searched;
}

/// The solution at a descent's end. One Newton step of 1 / sqrt towards unit length: an
/// evaluation's normalisation rounds a few times, and an axis-aligned minimiser should
/// come out as that axis exactly.
PairSolution solution(const Sample& at, PairPath path, int evaluations, double lower_bound) {
    const dvec3 n = at.n * (1.5 - 0.5 * glm::dot(at.n, at.n));
    return {at.h, n, at.xa, -at.xb, path, evaluations, lower_bound};
}

}  // namespace

// Lane twin: the end of PairLanes::solve (ellipsoid_pair_lanes.hpp), the same operations
// in the same order; the EllipsoidPairBatch tests fail when they differ.
PairSolution solve_pair(const PairFrame& frame) {
    PairFunction f(frame);
    Descent result = descend(f, f.at(first_guess(frame, f.support_matrix_b())));
    PairPath path = certificate(f, result);
    double lower_bound = result.at.h;
    if (path == PairPath::searched) {
        double unresolved = std::numeric_limits<double>::infinity();
        result = search(f, from_axes(f, result, frame), unresolved);
        lower_bound = std::min(result.at.h - kSearchTolerance, unresolved);
        if (unresolved < result.at.h - kSearchTolerance) path = PairPath::unproven;
    }
    return solution(result.at, path, f.evaluations, lower_bound);
}

PairSolution solve_pair(const PairFrame& frame, const dvec3& start) {
    PairFunction f(frame);
    const Descent warm = descend(f, f.at(start));
    const PairPath path = certificate(f, warm);
    if (path != PairPath::searched) return solution(warm.at, path, f.evaluations, warm.at.h);
    // Not certified: the cold call's path from its own first guess, so that no start can
    // make the answer worse than the cold call's (it is then the cold call's, bit for bit).
    PairSolution cold = solve_pair(frame);
    cold.evaluations += f.evaluations;
    return cold;
}

}  // namespace trackphys::detail
