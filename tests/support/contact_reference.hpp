#pragma once

// Reference ellipsoid-triangle penetration in long double, by a method independent of the
// kernel's root finding: sigma = min over unit u of g(u) = max_i u.q_i + ||D u||, whose
// minimiser has 3, 2 or 1 active vertices, so it is the smallest true g over
// - the face normals +-n;
// - every local minimum of u.q_i + ||D u|| on each edge's great circle (u orthogonal to
//   the edge), found by sampling the circle at 180 angles and bisecting the derivative;
// - every local minimum of u.q_i + ||D u|| on the sphere for each vertex, found by damped
//   Riemannian Newton descents from 14 spread directions plus the best sampled ones.
// A dense sampling of g over the sphere (Fibonacci points) checks that nothing lower was
// missed. Tests only.

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "support/long_double_vector.hpp"

namespace trackphys::test {

struct ReferenceContact {
    R depth;        ///< sigma
    V3 u;           ///< the minimising direction (ellipsoid frame)
    R runner_up;    ///< smallest g among candidates more than 1e-4 rad away from u
    R sampled_min;  ///< min of g over the dense sampling (>= depth)
    /// The least rise of g 1e-4 rad away from u (8 directions): a minimum flat to second
    /// order (a vertex at a center of curvature) fixes its direction only to ~eps^(1/4).
    R rise;
    int candidates;
};

class ContactReference {
  public:
    /// radii: any order (the frame's axes); q: the triangle in the ellipsoid's frame.
    ContactReference(const std::array<R, 3>& radii, const std::array<V3, 3>& q) : q_(q) {
        d2_ = {radii[0] * radii[0], radii[1] * radii[1], radii[2] * radii[2]};
    }

    ReferenceContact solve() {
        candidates_.clear();
        // Face.
        const V3 n = cross(q_[1] - q_[0], q_[2] - q_[0]);
        if (norm(n) > 0) {
            add(unit(n));
            add(unit(n) * R(-1));
        }
        for (int i = 0; i < 3; ++i) edge_minima(i);
        for (int i = 0; i < 3; ++i) vertex_minima(i);

        ReferenceContact result{};
        result.depth = INFINITY;
        for (const auto& [value, u] : candidates_)
            if (value < result.depth) {
                result.depth = value;
                result.u = u;
            }
        result.runner_up = INFINITY;
        for (const auto& [value, u] : candidates_)
            if (dot(u, result.u) < std::cos(R(1e-4)))
                result.runner_up = std::min(result.runner_up, value);
        const V3 helper = std::fabs(result.u.x) < 0.6L ? V3{1, 0, 0} : V3{0, 1, 0};
        const V3 t1 = unit(cross(result.u, helper));
        const V3 t2 = cross(result.u, t1);
        result.rise = INFINITY;
        for (int k = 0; k < 8; ++k) {
            const R angle = R(0.78539816339744830962L) * k;
            const V3 v = unit(result.u + (t1 * std::cos(angle) + t2 * std::sin(angle)) * R(1e-4));
            result.rise = std::min(result.rise, g(v) - result.depth);
        }
        result.sampled_min = INFINITY;
        const int samples = 600;
        for (int k = 0; k < samples; ++k)
            result.sampled_min = std::min(result.sampled_min, g(fibonacci(k, samples)));
        result.candidates = static_cast<int>(candidates_.size());
        return result;
    }

    R h(V3 u) const { return std::sqrt(d2_.x * u.x * u.x + d2_.y * u.y * u.y + d2_.z * u.z * u.z); }
    R g(V3 u) const { return std::max({dot(u, q_[0]), dot(u, q_[1]), dot(u, q_[2])}) + h(u); }

  private:
    static V3 fibonacci(int k, int count) {
        const R golden = R(3.883222077450933154693131L);  // pi (3 - sqrt 5)
        const R z = 1 - (2 * R(k) + 1) / R(count);
        const R rho = std::sqrt(1 - z * z);
        return {rho * std::cos(golden * R(k)), rho * std::sin(golden * R(k)), z};
    }

    void add(V3 u) { candidates_.push_back({g(u), u}); }

    // Edge i: phi(theta) = u.q_i + h(u), u = cos b1 + sin b2 orthogonal to the edge.
    void edge_minima(int i) {
        const V3 e = q_[(i + 1) % 3] - q_[i];
        if (!(norm(e) > 0)) return;
        const V3 dir = unit(e);
        const V3 helper = std::fabs(dir.x) < 0.6L ? V3{1, 0, 0} : V3{0, 1, 0};
        const V3 b1 = unit(cross(dir, helper));
        const V3 b2 = cross(dir, b1);
        const V3 q = q_[i];
        const auto u_of = [&](R t) { return b1 * std::cos(t) + b2 * std::sin(t); };
        const auto phi = [&](R t) { return dot(u_of(t), q) + h(u_of(t)); };
        const auto dphi = [&](R t) {
            const V3 u = u_of(t);
            const V3 du = b1 * (-std::sin(t)) + b2 * std::cos(t);
            const R hu = h(u);
            return dot(du, q) + (d2_.x * u.x * du.x + d2_.y * u.y * du.y + d2_.z * u.z * du.z) / hu;
        };
        const int count = 180;
        const R step = 2 * R(3.14159265358979323846264338327950288L) / count;
        std::vector<R> value(count);
        for (int k = 0; k < count; ++k) value[k] = phi(step * k);
        for (int k = 0; k < count; ++k) {
            const R before = value[(k + count - 1) % count], after = value[(k + 1) % count];
            if (value[k] > before || value[k] > after) continue;
            R lo = step * (k - 1), hi = step * (k + 1);
            if (dphi(lo) <= 0 && dphi(hi) >= 0) {
                for (int it = 0; it < 200; ++it) {
                    const R mid = (lo + hi) / 2;
                    if (mid <= lo || mid >= hi) break;
                    (dphi(mid) < 0 ? lo : hi) = mid;
                }
            } else {  // golden section on the sampled bracket
                for (int it = 0; it < 200; ++it) {
                    const R a = lo + (hi - lo) * 0.381966011250105151795L;
                    const R b = hi - (hi - lo) * 0.381966011250105151795L;
                    if (!(a < b)) break;
                    (phi(a) < phi(b) ? hi : lo) = phi(a) < phi(b) ? b : a;
                }
            }
            add(u_of((lo + hi) / 2));
        }
    }

    // Vertex i: local minima of phi(u) = u.q + h(u) on the sphere by damped Newton.
    void vertex_minima(int i) {
        const V3 q = q_[i];
        std::vector<V3> starts;
        for (int a = -1; a <= 1; a += 2)
            for (int b = -1; b <= 1; b += 2)
                for (int c = -1; c <= 1; c += 2) starts.push_back(unit(V3{R(a), R(b), R(c)}));
        for (int axis = 0; axis < 3; ++axis)
            for (const R side : {R(1), R(-1)})
                starts.push_back(
                    {axis == 0 ? side : 0, axis == 1 ? side : 0, axis == 2 ? side : 0});
        std::vector<std::pair<R, V3>> sampled;
        for (int k = 0; k < 100; ++k) {
            const V3 u = fibonacci(k, 100);
            sampled.push_back({dot(u, q) + h(u), u});
        }
        std::partial_sort(sampled.begin(), sampled.begin() + 4, sampled.end(),
                          [](const auto& a, const auto& b) { return a.first < b.first; });
        for (int k = 0; k < 4; ++k) starts.push_back(sampled[k].second);
        starts.push_back(unit(q * R(-1) + V3{1e-30L, 0, 0}));
        for (const V3& start : starts) add(descend(q, start));
    }

    V3 descend(V3 q, V3 u) const {
        const auto phi = [&](V3 v) { return dot(v, q) + h(v); };
        for (int it = 0; it < 200; ++it) {
            const R hu = h(u);
            const V3 d2u{d2_.x * u.x, d2_.y * u.y, d2_.z * u.z};
            const V3 grad_full = q + d2u * (1 / hu);
            const R radial = dot(u, grad_full);
            const V3 grad = grad_full - u * radial;
            // Tangent basis.
            const V3 helper = std::fabs(u.x) < 0.6L ? V3{1, 0, 0} : V3{0, 1, 0};
            const V3 t1 = unit(cross(u, helper));
            const V3 t2 = cross(u, t1);
            const auto hess = [&](V3 a, V3 b) {
                // a^T (D^2 / h - D^2u D^2u^T / h^3 - radial I) b on the tangent plane.
                const R dd = d2_.x * a.x * b.x + d2_.y * a.y * b.y + d2_.z * a.z * b.z;
                return dd / hu - dot(d2u, a) * dot(d2u, b) / (hu * hu * hu) - radial * dot(a, b);
            };
            const R g1 = dot(grad, t1), g2 = dot(grad, t2);
            if (std::sqrt(g1 * g1 + g2 * g2) < 1e-18L) break;
            const R h11 = hess(t1, t1), h12 = hess(t1, t2), h22 = hess(t2, t2);
            const R det = h11 * h22 - h12 * h12;
            R s1, s2;
            if (h11 > 0 && det > 0) {
                s1 = -(h22 * g1 - h12 * g2) / det;
                s2 = -(h11 * g2 - h12 * g1) / det;
            } else {
                s1 = -g1;
                s2 = -g2;
            }
            R length = std::sqrt(s1 * s1 + s2 * s2);
            if (length > 0.5L) {
                s1 *= 0.5L / length;
                s2 *= 0.5L / length;
            }
            if (!step_downhill_on_sphere(
                    u, t1, t2, s1, s2, [&](V3 v) { return phi(v); }, 60))
                break;
        }
        return u;
    }

    std::array<V3, 3> q_;
    V3 d2_;
    std::vector<std::pair<R, V3>> candidates_;
};

}  // namespace trackphys::test
