#pragma once

// Random and adversarial point-vs-ellipse(oid) cases for the root-finding tests and the
// benchmark: radii that are equal or nearly equal (the wheel has rx = ry), points on the
// axes, on and near the principal planes, at and near the center, on and near the surface,
// and far away. Deterministic for a given seed.

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <random>
#include <vector>

namespace trackphys::test {

/// The kind of point a case holds, for per-class statistics.
enum class PointClass { random, near_surface, on_plane, near_plane, on_axis, center, far, count };

inline const char* point_class_name(PointClass c) {
    static const char* names[] = {"random",  "near_surface", "on_plane", "near_plane",
                                  "on_axis", "center",       "far"};
    return names[static_cast<int>(c)];
}

template <int N>
struct PointCase {
    std::array<double, N> radii;  ///< sorted descending
    std::array<double, N> p;
    PointClass kind;
};

template <int N>
class PointCaseGenerator {
  public:
    explicit PointCaseGenerator(std::uint64_t seed) : rng_(seed) {}

    PointCase<N> next() {
        PointCase<N> c;
        c.radii = radii();
        const double r0 = c.radii[0];
        const int kind = pick(static_cast<int>(PointClass::count));
        c.kind = static_cast<PointClass>(kind);
        switch (c.kind) {
            case PointClass::random:
                for (double& x : c.p) x = uniform(-1.5, 1.5) * r0;
                break;
            case PointClass::near_surface: {
                // A surface point moved along its normal by +-10^-12..10^-1 r0.
                std::array<double, N> s = surface_point(c.radii);
                double norm = 0;
                std::array<double, N> n;
                for (int i = 0; i < N; ++i) {
                    n[i] = s[i] / (c.radii[i] * c.radii[i]);
                    norm += n[i] * n[i];
                }
                const double offset = (pick(2) ? 1 : -1) * std::pow(10.0, uniform(-12, -1)) * r0;
                for (int i = 0; i < N; ++i) c.p[i] = s[i] + offset * n[i] / std::sqrt(norm);
                break;
            }
            case PointClass::on_plane:
            case PointClass::near_plane:
                for (double& x : c.p) x = uniform(-1.5, 1.5) * r0;
                for (int i = 0; i < N; ++i)
                    if (pick(2) == 0 || i == N - 1)
                        c.p[i] *=
                            c.kind == PointClass::on_plane ? 0.0 : std::pow(10.0, uniform(-16, -3));
                break;
            case PointClass::on_axis: {
                c.p.fill(0.0);
                c.p[pick(N)] = uniform(-1.5, 1.5) * r0;
                break;
            }
            case PointClass::center:
                for (double& x : c.p)
                    x = pick(3) == 0 ? 0.0
                                     : uniform(-1, 1) * r0 * std::pow(10.0, uniform(-300, -2));
                break;
            case PointClass::far:
                for (double& x : c.p) x = uniform(-1, 1) * r0 * std::pow(10.0, uniform(1, 6));
                break;
            case PointClass::count:
                break;
        }
        return c;
    }

  private:
    std::array<double, N> radii() {
        std::array<double, N> r;
        switch (pick(6)) {
            case 0:  // wheel- and body-like
                if constexpr (N == 3)
                    r = pick(2) ? std::array<double, N>{0.35, 0.35, 0.15}
                                : std::array<double, N>{2.0, 1.0, 0.5};
                else
                    r = {0.35, 0.15};
                break;
            case 1:  // all equal
                r.fill(uniform(0.05, 3.0));
                break;
            case 2: {  // nearly equal neighbours
                for (double& x : r) x = uniform(0.05, 3.0);
                std::sort(r.begin(), r.end(), std::greater<>());
                const int i = pick(N - 1);
                r[i + 1] = r[i] * (1 - std::pow(10.0, uniform(-15, -2)));
                break;
            }
            case 3: {  // two exactly equal
                for (double& x : r) x = uniform(0.05, 3.0);
                std::sort(r.begin(), r.end(), std::greater<>());
                const int i = pick(N - 1);
                r[i + 1] = r[i];
                break;
            }
            default:
                for (double& x : r) x = uniform(0.05, 3.0);
                break;
        }
        std::sort(r.begin(), r.end(), std::greater<>());
        return r;
    }

    std::array<double, N> surface_point(const std::array<double, N>& r) {
        std::array<double, N> d;
        double norm = 0;
        for (double& x : d) {
            x = normal_(rng_);
            norm += x * x;
        }
        for (int i = 0; i < N; ++i) d[i] = r[i] * d[i] / std::sqrt(norm);
        return d;
    }

    double uniform(double lo, double hi) {
        return std::uniform_real_distribution<double>(lo, hi)(rng_);
    }
    int pick(int n) { return std::uniform_int_distribution<int>(0, n - 1)(rng_); }

    std::mt19937_64 rng_;
    std::normal_distribution<double> normal_;
};

}  // namespace trackphys::test
