#pragma once

// Reference ellipsoid-ellipsoid contact in long double, by a method independent of the
// kernel's certificates and search: the global minimum over unit n of
//     h(n) = (cA - cB).n + |D_A R_A^T n| + |D_B R_B^T n|
// taken over damped Riemannian Newton descents started from
// - every local minimum of h on a 40 x 80 latitude-longitude grid and its 6 lowest points;
// - every local minimum of h on the great circles orthogonal to the ellipsoids' long axes
//   (an elongated ellipsoid's h is a narrow valley along that circle, which a coarse grid
//   can straddle);
// - the centre line and the ellipsoids' axes, both ways.
// The grid's minimum checks that no sampled direction is lower. Tests only.

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "support/long_double_vector.hpp"
#include "trackphys/geometry/ellipsoid.hpp"

namespace trackphys::test {

namespace pair_reference {

/// One ellipsoid: centre, sorted axes (columns as rows here: axis[i]) and radii.
struct Body {
    V3 c;
    std::array<V3, 3> axis;
    std::array<R, 3> r;
};

inline Body body(const Ellipsoid& e) {
    Body b;
    b.c = {e.center().x, e.center().y, e.center().z};
    const glm::dmat3& m = e.sorted_axes();
    for (int i = 0; i < 3; ++i) {
        b.axis[i] = {m[i][0], m[i][1], m[i][2]};
        b.r[i] = e.sorted_radii()[i];
    }
    return b;
}

}  // namespace pair_reference

struct PairReferenceResult {
    long double depth;
    V3 n;                     ///< the minimiser (from A towards B): normal = -n
    V3 point;                 ///< the contact point (world)
    long double runner_up;    ///< lowest local minimum more than 1e-4 rad from n
    long double sampled_min;  ///< the grid's minimum (>= depth)
    /// The least rise of h 1e-4 rad away from n (8 directions): a minimum flat to second
    /// order fixes its direction only to ~eps^(1/4).
    long double rise;
};

class PairReference {
  public:
    PairReference(const Ellipsoid& a, const Ellipsoid& b)
        : a_(pair_reference::body(a)), b_(pair_reference::body(b)), d_(a_.c - b_.c) {}

    /// Support value of one body in direction n, and its support point relative to c.
    static R support(const pair_reference::Body& e, V3 n, V3* point = nullptr) {
        R sum = 0;
        V3 x{};
        for (int i = 0; i < 3; ++i) {
            const R w = dot(e.axis[i], n) * e.r[i];
            sum += w * w;
            x = x + e.axis[i] * (w * e.r[i]);
        }
        const R value = std::sqrt(sum);
        if (point) *point = x * (1 / value);
        return value;
    }

    R h(V3 n) const { return dot(d_, n) + support(a_, n) + support(b_, n); }

    PairReferenceResult solve() {
        minima_.clear();
        // Grid.
        constexpr int lat = 40, lon = 80;
        const R pi = 3.14159265358979323846264338327950288L;
        std::vector<R> value(lat * lon);
        std::vector<V3> dir(lat * lon);
        for (int i = 0; i < lat; ++i)
            for (int j = 0; j < lon; ++j) {
                const R theta = pi * (i + R(0.5)) / lat, phi = 2 * pi * j / lon;
                dir[i * lon + j] = {std::sin(theta) * std::cos(phi),
                                    std::sin(theta) * std::sin(phi), std::cos(theta)};
                value[i * lon + j] = h(dir[i * lon + j]);
            }
        std::vector<V3> starts;
        for (int i = 0; i < lat; ++i)
            for (int j = 0; j < lon; ++j) {
                const R v = value[i * lon + j];
                bool lowest = true;
                for (int di = -1; di <= 1 && lowest; ++di)
                    for (int dj = -1; dj <= 1; ++dj) {
                        const int ii = i + di;
                        if ((di == 0 && dj == 0) || ii < 0 || ii >= lat) continue;
                        if (value[ii * lon + (j + dj + lon) % lon] < v) {
                            lowest = false;
                            break;
                        }
                    }
                if (lowest) starts.push_back(dir[i * lon + j]);
            }
        std::vector<int> order(value.size());
        for (std::size_t k = 0; k < order.size(); ++k) order[k] = static_cast<int>(k);
        std::partial_sort(order.begin(), order.begin() + 6, order.end(),
                          [&](int x, int y) { return value[x] < value[y]; });
        for (int k = 0; k < 6; ++k) starts.push_back(dir[order[k]]);
        const R sampled_min = value[order[0]];
        // Great circles orthogonal to the long axes.
        for (const pair_reference::Body* e : {&a_, &b_}) circle_minima(e->axis[0], starts);
        // Centre line and axes.
        if (dot(d_, d_) > 0) {
            starts.push_back(unit(d_ * R(-1)));
            starts.push_back(unit(d_));
        }
        for (const pair_reference::Body* e : {&a_, &b_})
            for (int i = 0; i < 3; ++i) {
                starts.push_back(e->axis[i]);
                starts.push_back(e->axis[i] * R(-1));
            }
        for (const V3& s : starts) minima_.push_back(descend(s));

        PairReferenceResult out{};
        out.depth = INFINITY;
        for (const V3& n : minima_)
            if (h(n) < out.depth) {
                out.depth = h(n);
                out.n = n;
            }
        out.runner_up = INFINITY;
        for (const V3& n : minima_)
            if (dot(n, out.n) < std::cos(R(1e-4))) out.runner_up = std::min(out.runner_up, h(n));
        out.sampled_min = sampled_min;
        V3 t1, t2;
        basis(out.n, t1, t2);
        out.rise = INFINITY;
        for (int k = 0; k < 8; ++k) {
            const R angle = pi / 4 * k;
            const V3 v = unit(out.n + (t1 * std::cos(angle) + t2 * std::sin(angle)) * R(1e-4));
            out.rise = std::min(out.rise, h(v) - out.depth);
        }
        V3 xa, xb;
        support(a_, out.n, &xa);
        support(b_, out.n * R(-1), &xb);
        out.point = ((a_.c + xa) + (b_.c + xb)) * R(0.5);
        return out;
    }

  private:
    static void basis(V3 n, V3& t1, V3& t2) {
        const V3 helper = std::fabs(n.x) < 0.6L ? V3{1, 0, 0} : V3{0, 1, 0};
        t1 = unit(cross(n, helper));
        t2 = cross(n, t1);
    }

    void circle_minima(V3 axis, std::vector<V3>& starts) const {
        V3 b1, b2;
        basis(axis, b1, b2);
        constexpr int count = 72;
        const R step = 2 * R(3.14159265358979323846264338327950288L) / count;
        std::array<R, count> value;
        std::array<V3, count> dir;
        for (int k = 0; k < count; ++k) {
            dir[k] = b1 * std::cos(step * k) + b2 * std::sin(step * k);
            value[k] = h(dir[k]);
        }
        for (int k = 0; k < count; ++k)
            if (value[k] <= value[(k + 1) % count] && value[k] <= value[(k + count - 1) % count])
                starts.push_back(dir[k]);
    }

    // The gradient p(n) = d + x_A(n) + x_B(n) and the tangent Hessian
    // t_i^T ((M_A - x_A x_A^T) / a + (M_B - x_B x_B^T) / b) t_j - h(n) delta_ij.
    V3 gradient(V3 n) const {
        V3 xa, xb;
        support(a_, n, &xa);
        support(b_, n, &xb);
        return d_ + xa + xb;
    }

    static R quadratic(const pair_reference::Body& e, V3 s, V3 t) {
        R sum = 0;
        for (int i = 0; i < 3; ++i) sum += e.r[i] * e.r[i] * dot(e.axis[i], s) * dot(e.axis[i], t);
        return sum;
    }

    R hessian(V3 n, V3 s, V3 t) const {
        V3 xa, xb;
        const R a = support(a_, n, &xa), b = support(b_, n, &xb);
        return (quadratic(a_, s, t) - dot(xa, s) * dot(xa, t)) / a +
               (quadratic(b_, s, t) - dot(xb, s) * dot(xb, t)) / b - h(n) * dot(s, t);
    }

    V3 descend(V3 n) const {
        for (int it = 0; it < 100; ++it) {
            V3 t1, t2;
            basis(n, t1, t2);
            const V3 g = gradient(n);
            const R g1 = dot(g, t1), g2 = dot(g, t2);
            if (std::sqrt(g1 * g1 + g2 * g2) < 1e-17L * (1 + std::sqrt(dot(g, g)))) break;
            const R h11 = hessian(n, t1, t1), h12 = hessian(n, t1, t2), h22 = hessian(n, t2, t2);
            const R det = h11 * h22 - h12 * h12;
            R s1, s2;
            if (h11 > 0 && det > 0) {
                s1 = -(h22 * g1 - h12 * g2) / det;
                s2 = -(h11 * g2 - h12 * g1) / det;
            } else {
                const R scale = std::fabs(h11) + std::fabs(h22) + std::fabs(h12) + 1e-30L;
                s1 = -g1 / scale;
                s2 = -g2 / scale;
            }
            const R length = std::sqrt(s1 * s1 + s2 * s2);
            if (length > 0.3L) {
                s1 *= 0.3L / length;
                s2 *= 0.3L / length;
            }
            // Below ~1e-6 rad h cannot rank Newton steps any more (it changes by their
            // square); the gradient still can.
            if (h11 > 0 && det > 0 && length < 1e-6L) {
                if (length < 1e-17L) break;
                n = unit(n + t1 * s1 + t2 * s2);
                continue;
            }
            if (!step_downhill_on_sphere(
                    n, t1, t2, s1, s2, [&](V3 v) { return h(v); }, 80))
                break;
        }
        return n;
    }

    pair_reference::Body a_, b_;
    V3 d_;
    std::vector<V3> minima_;
};

}  // namespace trackphys::test
