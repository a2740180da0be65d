#pragma once

// Reference critical points of the distance from a point to an ellipse (N = 2) or
// ellipsoid (N = 3), in long double by plain bisection. Tests only.
//
// Roots of f(t) = sum (r_i p_i / (r_i^2 + t))^2 - 1 are bracketed interval by interval in
// the offset from a pole (so that t near a pole keeps its digits): beyond the outer poles f
// is monotone; between two poles f is convex, so bisection on f' finds its minimum and then
// bisection on f finds 0 or 2 roots. Every bisection runs until the bracket stops shrinking.
// Coordinates that are exactly 0 add Eberly's closed-form points.

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace trackphys::test {

using Real = long double;

template <int N>
struct RefCriticalPoint {
    std::array<Real, N> x;  ///< surface point
    Real offset;            ///< n . (p - x), n the outward unit normal at x
};

template <int N>
class ReferenceSolver {
  public:
    ReferenceSolver(const std::array<double, N>& r, const std::array<double, N>& p) {
        for (int i = 0; i < N; ++i) {
            r_[i] = r[i];
            p_[i] = p[i];
            a_[i] = r_[i] * std::fabs(p_[i]);
        }
    }

    /// Every critical point (the closed-form families by their axis points).
    std::vector<RefCriticalPoint<N>> all() const {
        std::vector<RefCriticalPoint<N>> out;
        std::vector<int> poles;  // first index of each active group of equal radii
        for (int i = 0; i < N; ++i) {
            if (i > 0 && r_[i] == r_[i - 1]) continue;
            bool active = false;
            for (int j = i; j < N && r_[j] == r_[i]; ++j) active = active || a_[j] > 0;
            if (active) poles.push_back(i);
        }
        if (!poles.empty()) {
            add_root(poles.back(), +1, outer_root(poles.back(), +1), out);
            add_root(poles.front(), -1, outer_root(poles.front(), -1), out);
            for (std::size_t k = 0; k + 1 < poles.size(); ++k)
                middle_roots(poles[k], poles[k + 1], out);
        }
        for (int g = 0; g < N; ++g) {
            if (g > 0 && r_[g] == r_[g - 1]) continue;
            bool active = false;
            int members = 0;
            for (int j = g; j < N && r_[j] == r_[g]; ++j) {
                active = active || a_[j] > 0;
                ++members;
            }
            if (!active) closed_form(g, members, out);
        }
        return out;
    }

    /// The closest point (smallest |offset|).
    RefCriticalPoint<N> closest() const {
        const std::vector<RefCriticalPoint<N>> points = all();
        return *std::min_element(points.begin(), points.end(), [](const auto& a, const auto& b) {
            return std::fabs(a.offset) < std::fabs(b.offset);
        });
    }

  private:
    // S(eta) = sum (a_i / (c_i + eta))^2 with c_i = s (r_i^2 - r_pole^2).
    Real c_of(int i, int pole, int s) const { return s * (r_[i] - r_[pole]) * (r_[i] + r_[pole]); }
    Real S(int pole, int s, Real eta) const {
        Real sum = 0;
        for (int i = 0; i < N; ++i)
            if (a_[i] > 0) {
                const Real v = a_[i] / (c_of(i, pole, s) + eta);
                sum += v * v;
            }
        return sum;
    }
    Real dS(int pole, int s, Real eta) const {
        Real sum = 0;
        for (int i = 0; i < N; ++i)
            if (a_[i] > 0) {
                const Real w = c_of(i, pole, s) + eta;
                const Real v = a_[i] / w;
                sum -= 2 * v * v / w;
            }
        return sum;
    }

    // Bisection for S = 1 on (lo, hi); `decreasing`: S > 1 at lo.
    Real bisect_S(int pole, int s, Real lo, Real hi, bool decreasing) const {
        for (int k = 0; k < 20000; ++k) {
            const Real mid = lo + (hi - lo) / 2;
            if (mid <= lo || mid >= hi) break;
            const bool above = S(pole, s, mid) > 1;
            if (above == decreasing)
                lo = mid;
            else
                hi = mid;
        }
        return lo + (hi - lo) / 2;
    }

    Real outer_root(int pole, int s) const {
        Real total = 0;
        for (int i = 0; i < N; ++i) total += a_[i] * a_[i];
        Real hi = std::sqrt(total);
        while (S(pole, s, hi) > 1) hi *= 2;  // all other poles lie behind: S <= total / eta^2
        return bisect_S(pole, s, 0, hi, true);
    }

    void middle_roots(int left, int right, std::vector<RefCriticalPoint<N>>& out) const {
        const Real length = (r_[left] - r_[right]) * (r_[left] + r_[right]);
        // S is convex on (0, length): its minimum where S' changes sign.
        Real lo = 0, hi = length;
        for (int k = 0; k < 20000; ++k) {
            const Real mid = lo + (hi - lo) / 2;
            if (mid <= lo || mid >= hi) break;
            (dS(left, +1, mid) < 0 ? lo : hi) = mid;
        }
        const Real bottom = lo + (hi - lo) / 2;
        if (!(S(left, +1, bottom) < 1)) return;
        // Each root in the offset from its nearer pole, so that a root next to the right pole
        // keeps its digits.
        add_root(left, +1, bisect_S(left, +1, 0, bottom, true), out);
        add_root(right, -1, bisect_S(right, -1, 0, length - bottom, true), out);
    }

    void add_root(int pole, int s, Real eta, std::vector<RefCriticalPoint<N>>& out) const {
        RefCriticalPoint<N> cp;
        std::array<Real, N> n{};
        for (int i = 0; i < N; ++i) {
            const Real w = s * (c_of(i, pole, s) + eta);  // r_i^2 + t
            cp.x[i] = a_[i] > 0 ? r_[i] * r_[i] * p_[i] / w : 0;
            n[i] = a_[i] > 0 ? p_[i] / w : 0;
        }
        finish(cp, n, out);
    }

    void closed_form(int g, int members, std::vector<RefCriticalPoint<N>>& out) const {
        std::array<Real, N> x{};
        Real used = 0;
        for (int j = 0; j < N; ++j) {
            if (j >= g && j < g + members) continue;
            x[j] = r_[j] * r_[j] * p_[j] / ((r_[j] - r_[g]) * (r_[j] + r_[g]));
            used += (x[j] / r_[j]) * (x[j] / r_[j]);
        }
        if (!(used < 1)) return;
        const Real rho = r_[g] * std::sqrt(1 - used);
        for (int m = g; m < g + members; ++m)
            for (const Real side : {Real(1), Real(-1)}) {
                RefCriticalPoint<N> cp;
                std::array<Real, N> n{};
                for (int i = 0; i < N; ++i) {
                    cp.x[i] = (i >= g && i < g + members) ? (i == m ? side * rho : 0) : x[i];
                    n[i] = cp.x[i] / (r_[i] * r_[i]);
                }
                finish(cp, n, out);
            }
    }

    void finish(RefCriticalPoint<N>& cp, const std::array<Real, N>& n,
                std::vector<RefCriticalPoint<N>>& out) const {
        Real norm = 0;
        for (int i = 0; i < N; ++i) norm += n[i] * n[i];
        norm = std::sqrt(norm);
        Real offset = 0;
        for (int i = 0; i < N; ++i) offset += n[i] / norm * (p_[i] - cp.x[i]);
        cp.offset = offset;
        out.push_back(cp);
    }

    std::array<Real, N> r_{};
    std::array<Real, N> p_{};
    std::array<Real, N> a_{};
};

}  // namespace trackphys::test
