#pragma once

// The critical points of the distance from a point p to an ellipse (N = 2) or ellipsoid
// (N = 3) in its sorted frame, radii r_0 >= ... >= r_{N-1} > 0 (docs/design.md#root-finding).
// Internal: the public wrappers are point_ellipse.hpp and point_ellipsoid.hpp, and the
// contact kernel uses this directly.
//
// A surface point x is critical when p lies on its normal line: p = x + t D^-2 x, so
// x_i = r_i^2 p_i / (r_i^2 + t) and t is a root of
//     f(t) = sum_i (r_i p_i / (r_i^2 + t))^2 - 1,
// which has a pole at t = -r_i^2 for every p_i != 0 ("active" terms).
//
// The robust scheme works beside one pole G at a time, in the offset eta >= 0 from it:
// t = -r_G^2 + s eta for a climb in direction s = +1 (towards larger t) or s = -1. Then
//     r_i^2 + t = s (c_i + eta),   c_i = s (r_i - r_G)(r_i + r_G),
// so f + 1 = S(eta) = sum (a_i / (c_i + eta))^2 with a_i = r_i |p_i|, every offset formed as
// a product so that equal and nearly equal radii need no special case. On the interval
// between G and the next active pole ahead (c_i < 0), each |c_i + eta| is affine and
//     h(eta) = S^(-1/2) - 1 = F(|c + eta| / a),   F(w) = (sum w_i^-2)^(-1/2),
// is concave because F is a power mean of exponent -2 (concave on the positive orthant).
// h -> -1 at G, so from any eta0 with h(eta0) <= 0 left of the first root, Newton on h
// climbs monotonically to that root (the tangent of a concave function lies above it, so
// the Newton point never passes the root). eta0 = max over terms behind or at G of
// (a_i - c_i) has one term >= 1, so S >= 1 on all of (0, eta0]. If instead the tangent's
// zero passes the next pole, or h' <= 0 while h < 0, concavity proves the interval holds
// no root in that direction. Each loop is capped.
//
// Which roots are local minima of u . p + ||D u|| at u = -n (the only ones a contact can
// rest on; for p inside, the local minima of the distance |p - x|): the Lagrangian Hessian
// I + t D^-2 restricted to the tangent plane is positive definite iff no factor
// w_i = r_i^2 + t is negative, or exactly one is and f'(t) > 0 (its determinant is
// det(I + t D^-2) * (-f'(t)/2) / |D^-2 x|^2, and interlacing allows at most one negative
// eigenvalue then). f' > 0 holds exactly for roots reached by a climb towards smaller t (f
// rises to +inf at the pole it started from).
//
// Coordinates with p_i = 0 exactly add the closed-form solutions at t = -r_i^2 (Eberly):
// the other coordinates are fixed, x_j = r_j^2 p_j / (r_j^2 - r_i^2), and x_i takes the
// remaining +-r_i sqrt(1 - sum (x_j / r_j)^2) when that is real. A group of equal radii
// with all p = 0 gives a circle or sphere of such points; its axis points represent it.

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace trackphys::detail {

/// Newton steps allowed per root; the robust climb needs <= ~20 for a simple root.
inline constexpr int kClimbCap = 64;
/// A climb stops once a Newton step is below this fraction of the offset: with quadratic
/// convergence the remaining error is then far below one ulp.
inline constexpr double kClimbRelativeStep = 1e-8;
/// The contact kernel's climbs (closest point, other minimum) also stop once the predicted
/// error is below this fraction of eta: directions then carry ~1e-10 rad (the contract asks
/// 1e-6 rad), depths ~1e-20 m (second order: a candidate's g is evaluated exactly at its
/// direction). Saves the last Newton step of most climbs (vertex 5.0 -> 4.2 steps, edge
/// 3.9 -> 3.1).
inline constexpr double kContactPredicted = 1e-10;

struct ClimbResult {
    double eta;
    int iterations;
    bool found;
};

/// S = sum (a_i / w_i)^2 and T = sum a_i^2 / w_i^3 at a point of the climb, given the
/// inverses inv_w_i = 1 / w_i of w_i = c_i + eta, and the Newton step on h = S^-1/2 - 1
/// there: h' = S^-3/2 T, so step = (S / T)(sqrt(S) - 1). The division and the square root
/// are independent: one latency on the climb's chain instead of two in a row.
struct NewtonStep {
    double s, t, step;
};

template <int N>
inline NewtonStep newton_step(const std::array<double, N>& a, const std::array<double, N>& inv_w) {
    double s = 0.0;
    double t = 0.0;
    for (int i = 0; i < N; ++i) {
        const double v = a[i] * inv_w[i];
        const double v2 = v * v;
        s += v2;
        t += v2 * inv_w[i];
    }
    return {s, t, (s / t) * (std::sqrt(s) - 1.0)};
}

/// Climbs h(eta) from eta0 to its first root below eta_max. Inactive terms must carry
/// a = 0 and c = 1 (so they add exactly 0). Stops once a step is below kClimbRelativeStep
/// of eta, or, when predicted > 0, once the error left after a step, as quadratic
/// convergence predicts it from the last two steps (e_{k+1} = e_k (e_k / e_{k-1})^2), is
/// below predicted * eta. previous_step: the step that led to eta0, if any (else 0).
template <int N>
inline ClimbResult climb(const std::array<double, N>& a, const std::array<double, N>& c,
                         double eta0, double eta_max, double predicted = 0.0,
                         double previous_step = 0.0) {
    double eta = eta0;
    if (!(eta < eta_max)) return {eta, 0, false};
    for (int k = 1; k <= kClimbCap; ++k) {
        std::array<double, N> inv_w;
        for (int i = 0; i < N; ++i) inv_w[i] = 1.0 / (c[i] + eta);  // one division per term
        const NewtonStep n = newton_step<N>(a, inv_w);
        if (n.s <= 1.0) return {eta, k, true};     // h >= 0: at the root up to rounding
        if (!(n.t > 0.0)) return {eta, k, false};  // past the top of h while h < 0
        const double next = eta + n.step;
        if (!(next < eta_max)) return {next, k, false};
        if (n.step <= kClimbRelativeStep * eta) return {next, k, true};
        const double ratio = n.step / previous_step;  // infinite without a previous step
        if (n.step * ratio * ratio <= predicted * eta) return {next, k, true};
        previous_step = n.step;
        eta = next;
    }
    return {eta, kClimbCap, true};
}

/// The same climb on the rightward interval of the last active pole (no pole ahead, so h is
/// concave on all of (0, inf)), started from a guess on either side of the root: one Newton
/// step from the guess lands at or left of the root, since the tangent of a concave function
/// lies above it (from the right, h > 0, the step goes left to where the tangent, which is
/// >= h, reaches 0: h <= 0 there). Clamped to eta0 (itself left of the root), it is a valid
/// start for the monotone climb. inv_w: the inverses 1 / (c_i + guess), which the caller has
/// at hand for its guess.
template <int N>
inline ClimbResult climb_from_guess(const std::array<double, N>& a, const std::array<double, N>& c,
                                    double eta0, double guess, const std::array<double, N>& inv_w,
                                    double predicted) {
    const double infinity = std::numeric_limits<double>::infinity();
    if (!(guess > eta0)) return climb<N>(a, c, eta0, infinity, predicted);
    const NewtonStep n = newton_step<N>(a, inv_w);
    if (!(n.t > 0.0)) return climb<N>(a, c, eta0, infinity, predicted);
    const double next = std::max(guess + n.step, eta0);
    if (std::abs(n.step) <= kClimbRelativeStep * guess) return {next, 1, true};
    ClimbResult rest = climb<N>(a, c, next, infinity, predicted);
    rest.iterations += 1;
    return rest;
}

/// The closest surface point's outward normal direction, unnormalised, for the contact
/// kernel: m_i = p_i / (r_i^2 + t) = x_i / r_i^2, with |m|^2, support2 = sum r_i^2 m_i^2 =
/// h(m)^2 (= x . m) and offset_times_length = |m| times the signed distance n . (p - x).
/// Left unnormalised so that the caller can take |m| and h(m) = |m| h(n) as independent
/// square roots.
template <int N>
struct ClosestDirection {
    std::array<double, N> m;
    double norm2;
    double support2;
    double offset_times_length;
};

/// The closest point when p's last coordinate is not 0 (the smallest radius' pole is
/// active, so the closest point is the rightward root from it and nothing else can be):
/// the hot path of the contact kernel, without the general solver's bookkeeping. pole[i] =
/// (r_i - r_last)(r_i + r_last), inv_r2[i] = 1 / r_i^2; inputs at unit scale (no
/// rescaling here). The climb starts from t = 0 (eta = r_last^2, where w_i = r_i^2), the
/// root for a point on the surface: contacts are shallow, and the first step from there
/// is exact for a sphere (h is linear then). Adds Newton steps to iterations.
template <int N>
inline ClosestDirection<N> closest_direction_fast(const std::array<double, N>& r,
                                                  const std::array<double, N>& pole,
                                                  const std::array<double, N>& inv_r2,
                                                  const std::array<double, N>& p, int& iterations) {
    std::array<double, N> a;
    double eta0 = 0.0;
    for (int i = 0; i < N; ++i) {
        a[i] = r[i] * std::abs(p[i]);
        eta0 = std::max(eta0, a[i] - pole[i]);
    }
    const ClimbResult root =
        climb_from_guess<N>(a, pole, eta0, r[N - 1] * r[N - 1], inv_r2, kContactPredicted);
    iterations += root.iterations;
    // x_i = r_i^2 p_i / w_i and m_i = p_i / w_i with w_i = pole_i + eta.
    ClosestDirection<N> out;
    out.norm2 = 0.0;
    out.support2 = 0.0;
    double p_dot_m = 0.0;
    for (int i = 0; i < N; ++i) {
        const double w = pole[i] + root.eta;
        out.m[i] = p[i] / w;
        out.norm2 += out.m[i] * out.m[i];
        out.support2 += r[i] * r[i] * out.m[i] * out.m[i];
        p_dot_m += p[i] * out.m[i];
    }
    out.offset_times_length = p_dot_m - out.support2;
    return out;
}

/// The other local minimum, if any, when p's last coordinate is not 0: the first root left
/// of the smallest radius' pole (climbing towards smaller t, so f' > 0 there), a minimum when
/// exactly one factor r_i^2 + t = pole_i - eta is negative. pole as for
/// closest_direction_fast; writes the outward unit normal and returns whether it exists.
template <int N>
inline bool other_minimum_normal_fast(const std::array<double, N>& r,
                                      const std::array<double, N>& pole,
                                      const std::array<double, N>& p, std::array<double, N>& normal,
                                      int& iterations) {
    std::array<double, N> a;
    std::array<double, N> c;
    double eta0 = 0.0;
    double eta_max = std::numeric_limits<double>::infinity();
    for (int i = 0; i < N; ++i) {
        a[i] = r[i] * std::abs(p[i]);
        c[i] = a[i] > 0.0 ? -pole[i] : 1.0;  // inactive terms add exactly 0
        if (a[i] > 0.0 && pole[i] > 0.0) eta_max = std::min(eta_max, pole[i]);
        if (pole[i] == 0.0) eta0 = std::max(eta0, a[i]);
    }
    const ClimbResult root = climb<N>(a, c, eta0, eta_max, kContactPredicted);
    iterations += root.iterations;
    if (!root.found) return false;
    int negative = 0;
    double norm2 = 0.0;
    for (int i = 0; i < N; ++i) {
        const double w = pole[i] - root.eta;  // r_i^2 + t
        negative += w < 0.0;
        normal[i] = a[i] > 0.0 ? p[i] / w : 0.0;
        norm2 += normal[i] * normal[i];
    }
    if (negative != 1) return false;
    const double inv = 1.0 / std::sqrt(norm2);
    for (int i = 0; i < N; ++i) normal[i] *= inv;
    return true;
}

template <int N>
struct CriticalPoint {
    std::array<double, N> x;  ///< surface point (sorted frame, input scale)
    std::array<double, N> n;  ///< outward unit normal at x
    double offset;            ///< n . (p - x): the signed distance along the normal
    bool local_min;           ///< u = -n locally minimises u . p + ||D u|| over unit u
};

template <int N>
struct CriticalPoints {
    std::array<CriticalPoint<N>, 2 * N + 2> points;
    int count = 0;
    int iterations = 0;  ///< Newton steps over all climbs
};

/// Which critical points to compute.
enum class CriticalSet {
    closest,       ///< the closest surface point only (one entry)
    other_minima,  ///< the local minima except the closest point's root
    all,           ///< every critical point
};

template <int N>
class CriticalSolver {
  public:
    /// r: radii sorted descending, all > 0 and finite; p: any finite point.
    CriticalSolver(const std::array<double, N>& r, const std::array<double, N>& p) {
        // Scale by a power of two (exact) when lengths leave the comfortable range, so that
        // squares neither overflow nor lose precision to subnormals.
        double m = r[0];
        for (int i = 0; i < N; ++i) m = std::max(m, std::abs(p[i]));
        scale_ = 1.0;
        if (m > 0x1p200 || r[N - 1] < 0x1p-200) {
            const int e = std::ilogb(m);
            scale_ = std::ldexp(1.0, e);
        }
        for (int i = 0; i < N; ++i) {
            r_[i] = r[i] / scale_;
            p_[i] = p[i] / scale_;
            y_[i] = std::abs(p_[i]);
            sign_[i] = p_[i] < 0.0 ? -1.0 : 1.0;
            a_[i] = r_[i] * y_[i];
        }
        // Groups of equal radii; a group is an active pole when any member has a > 0.
        for (int i = 0; i < N; ++i) {
            group_[i] = (i > 0 && r_[i] == r_[i - 1]) ? group_[i - 1] : i;
            if (a_[i] > 0.0) active_group_[group_[i]] = true;
        }
    }

    void solve(CriticalSet which, CriticalPoints<N>& out) {
        out.count = 0;
        out.iterations = 0;
        int poles[N];
        int pole_count = 0;
        for (int i = 0; i < N; ++i)
            if (group_[i] == i && active_group_[i]) poles[pole_count++] = i;

        if (pole_count > 0) {
            const int last = poles[pole_count - 1];
            if (which != CriticalSet::other_minima) climb_from(last, +1, out, which);
            if (which == CriticalSet::all) {
                climb_from(poles[0], -1, out, which);
                for (int k = 0; k + 1 < pole_count; ++k) {
                    climb_from(poles[k], +1, out, which);
                    climb_from(poles[k + 1], -1, out, which);
                }
            } else if (which != CriticalSet::closest && group_[N - 1] == last) {
                // Only a root with at most one negative factor can be a minimum, so only the
                // first root left of the smallest radius' pole (f' > 0 there) can be one
                // besides the closest point; left of any other pole two factors are < 0.
                climb_from(last, -1, out, which);
            }
        }
        for (int g = 0; g < N; ++g) {
            if (group_[g] != g || active_group_[g]) continue;
            closed_form(g, out, which);
        }
        if (which == CriticalSet::closest) keep_closest(out);
    }

  private:
    int negatives(double t_offset_sign, int pole, double eta) const {
        // Number of factors r_i^2 + t < 0 at t = -r_pole^2 + s eta.
        int count = 0;
        for (int i = 0; i < N; ++i) {
            const double w = (r_[i] - r_[pole]) * (r_[i] + r_[pole]) + t_offset_sign * eta;
            if (w < 0.0) ++count;
        }
        return count;
    }

    void climb_from(int pole, int direction, CriticalPoints<N>& out, CriticalSet which) {
        const double s = direction;
        std::array<double, N> a{};
        std::array<double, N> c{};
        double eta0 = 0.0;
        double eta_max = std::numeric_limits<double>::infinity();
        for (int i = 0; i < N; ++i) {
            const double ci = s * (r_[i] - r_[pole]) * (r_[i] + r_[pole]);
            if (a_[i] > 0.0) {
                a[i] = a_[i];
                c[i] = ci;
                if (ci >= 0.0)
                    eta0 = std::max(eta0, a_[i] - ci);
                else
                    eta_max = std::min(eta_max, -ci);
            } else {
                a[i] = 0.0;
                c[i] = 1.0;
            }
        }
        const ClimbResult root = climb<N>(a, c, eta0, eta_max);
        out.iterations += root.iterations;
        if (!root.found) return;
        const int neg = negatives(s, pole, root.eta);
        const bool local_min = neg == 0 || (neg == 1 && direction < 0);
        if (which == CriticalSet::other_minima && !local_min) return;
        CriticalPoint<N>& cp = out.points[out.count++];
        double norm2 = 0.0;
        for (int i = 0; i < N; ++i) {
            if (a_[i] > 0.0) {
                // x_i = r_i^2 y_i / (r_i^2 + t), r_i^2 + t = s (c_i + eta).
                const double w = s * (c[i] + root.eta);
                cp.x[i] = sign_[i] * r_[i] * r_[i] * y_[i] / w;
                cp.n[i] = sign_[i] * y_[i] / w;  // x_i / r_i^2
            } else {
                cp.x[i] = 0.0;
                cp.n[i] = 0.0;
            }
            norm2 += cp.n[i] * cp.n[i];
        }
        finish(cp, norm2, local_min);
    }

    void closed_form(int g, CriticalPoints<N>& out, CriticalSet which) {
        // t = -r_g^2: coordinates outside the group are fixed, the group's lie on a sphere.
        std::array<double, N> x{};
        double used = 0.0;
        int neg = 0;
        int members = 0;
        for (int j = 0; j < N; ++j) {
            if (group_[j] == g) {
                ++members;
                continue;
            }
            const double w = (r_[j] - r_[g]) * (r_[j] + r_[g]);
            if (w < 0.0) ++neg;
            x[j] = sign_[j] * r_[j] * r_[j] * y_[j] / w;
            used += (x[j] / r_[j]) * (x[j] / r_[j]);
        }
        const double remaining = 1.0 - used;
        if (!(remaining > 0.0)) return;
        const bool local_min = neg == 0;
        if (which == CriticalSet::other_minima && !local_min) return;
        const double rho = r_[g] * std::sqrt(remaining);
        for (int m = g; m < g + members; ++m) {
            for (const double side : {1.0, -1.0}) {
                CriticalPoint<N>& cp = out.points[out.count++];
                double norm2 = 0.0;
                for (int i = 0; i < N; ++i) {
                    cp.x[i] = group_[i] == g ? (i == m ? side * rho : 0.0) : x[i];
                    cp.n[i] = cp.x[i] / (r_[i] * r_[i]);
                    norm2 += cp.n[i] * cp.n[i];
                }
                finish(cp, norm2, local_min);
            }
        }
    }

    void finish(CriticalPoint<N>& cp, double norm2, bool local_min) const {
        const double inv = 1.0 / std::sqrt(norm2);
        double offset = 0.0;
        for (int i = 0; i < N; ++i) {
            cp.n[i] *= inv;
            offset += cp.n[i] * (p_[i] - cp.x[i]);
            cp.x[i] *= scale_;
        }
        cp.offset = offset * scale_;
        cp.local_min = local_min;
    }

    // The closest point is the critical point nearest to p (|offset| = |p - x| there). It is
    // the last pole's rightward root unless that root has a negative factor, in which case
    // a closed form wins (Eberly); comparing keeps the choice robust at the boundary.
    static void keep_closest(CriticalPoints<N>& out) {
        int best = 0;
        for (int k = 1; k < out.count; ++k)
            if (std::abs(out.points[k].offset) < std::abs(out.points[best].offset)) best = k;
        if (out.count > 1) out.points[0] = out.points[best];
        out.count = std::min(out.count, 1);
    }

    double scale_;
    std::array<double, N> r_{};
    std::array<double, N> p_{};
    std::array<double, N> y_{};
    std::array<double, N> sign_{};
    std::array<double, N> a_{};
    std::array<int, N> group_{};
    std::array<bool, N> active_group_{};
};

}  // namespace trackphys::detail
