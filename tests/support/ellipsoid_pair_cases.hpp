#pragma once

// Ellipsoid pairs for the ellipsoid-ellipsoid tests, fuzzer seeds and benchmark, by
// family: spheres, sphere-ellipsoid, car-like, grazing, deep, elongated, crossing,
// coincident centres, identical ellipsoids, scaled and far apart. Deterministic for a
// given seed.

#include <cmath>
#include <random>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

#include "support/sanitized.hpp"
#include "trackphys/geometry/ellipsoid.hpp"

namespace trackphys::test {

enum class PairKind {
    spheres,           ///< two spheres at any distance from coincident to 1 m apart
    sphere_ellipsoid,  ///< a sphere and an ellipsoid, depth about -0.5..0.5 m
    car_like,          ///< semi-axes 0.2-2.5 m, depth about -0.3..0.3 m
    grazing,           ///< car-like, |depth| < 1e-6 m
    deep,              ///< one centre inside the other ellipsoid
    elongated,         ///< semi-axis ratios up to 100:1, shallow to deep
    crossing,          ///< two elongated ellipsoids crossing near their centres
    coincident,        ///< the same centre
    identical,         ///< the same shape and orientation, offset
    scaled,            ///< a car-like pair scaled by 1e-3..1e3
    far,               ///< 10 m to 10 km apart, up to 1 km from the origin
    count
};

inline const char* pair_kind_name(PairKind k) {
    static const char* names[] = {"spheres",   "sphere_ellipsoid", "car_like", "grazing",
                                  "deep",      "elongated",        "crossing", "coincident",
                                  "identical", "scaled",           "far"};
    return names[static_cast<int>(k)];
}

struct PairCase {
    Ellipsoid a, b;
    PairKind kind;
};

class PairCaseGenerator {
  public:
    explicit PairCaseGenerator(std::uint64_t seed) : rng_(seed) {}

    double uniform(double lo, double hi) {
        return std::uniform_real_distribution<double>(lo, hi)(rng_);
    }
    double log_uniform(double lo, double hi) {
        return std::exp(uniform(std::log(lo), std::log(hi)));
    }

    glm::dvec3 unit_vector() {
        std::normal_distribution<double> g;
        for (int tries = 0; tries < 64; ++tries) {
            const glm::dvec3 v(g(rng_), g(rng_), g(rng_));
            const double length = glm::length(v);
            if (length > 1e-3) return v / length;
        }
        return {0.0, 1.0, 0.0};
    }

    glm::dquat rotation() {
        std::normal_distribution<double> g;
        return glm::normalize(glm::dquat(g(rng_), g(rng_), g(rng_), g(rng_)));
    }

    glm::dvec3 car_axes() { return {uniform(0.2, 2.5), uniform(0.2, 2.5), uniform(0.2, 2.5)}; }

    /// Semi-axes with the largest over the smallest up to `ratio`.
    glm::dvec3 elongated_axes(double ratio) {
        const double big = uniform(0.5, 2.5);
        return {big, big / log_uniform(1.0, ratio), big / log_uniform(1.0, ratio)};
    }

    /// a's shape placed against b so that they touch with normal u (the direction to move
    /// a) and then pushed by `depth` along -u: exactly `depth` apart when negative, about
    /// `depth` deep when positive.
    Ellipsoid placed(const glm::dvec3& a_axes, const glm::dquat& a_rotation, const Ellipsoid& b,
                     double depth) {
        const Ellipsoid shape({0.0, 0.0, 0.0}, a_rotation, a_axes);
        const glm::dvec3 u = unit_vector();
        const glm::dvec3 center = support_point(b, u) - support_point(shape, -u) - depth * u;
        return Ellipsoid(center, a_rotation, a_axes);
    }

    PairCase make(PairKind kind) {
        switch (kind) {
            case PairKind::spheres: {
                const double ra = uniform(0.1, 3.0), rb = uniform(0.1, 3.0);
                const Ellipsoid b(origin(), rotation(), glm::dvec3(rb));
                const glm::dvec3 c = b.center() + unit_vector() * uniform(0.0, ra + rb + 1.0);
                return {Ellipsoid(c, rotation(), glm::dvec3(ra)), b, kind};
            }
            case PairKind::sphere_ellipsoid: {
                const Ellipsoid b(origin(), rotation(), car_axes());
                return {placed(glm::dvec3(uniform(0.2, 2.0)), rotation(), b, uniform(-0.5, 0.5)), b,
                        kind};
            }
            case PairKind::car_like: {
                const Ellipsoid b(origin(), rotation(), car_axes());
                return {placed(car_axes(), rotation(), b, uniform(-0.3, 0.3)), b, kind};
            }
            case PairKind::grazing: {
                const Ellipsoid b(origin(), rotation(), car_axes());
                const double depth = (uniform(0, 1) < 0.5 ? -1 : 1) * log_uniform(1e-12, 1e-6);
                return {placed(car_axes(), rotation(), b, depth), b, kind};
            }
            case PairKind::deep: {
                const Ellipsoid b(origin(), rotation(), car_axes());
                const glm::dvec3 inside =
                    b.sorted_axes() * (b.sorted_radii() * unit_vector() * uniform(0.0, 0.99));
                return {Ellipsoid(b.center() + inside, rotation(), car_axes()), b, kind};
            }
            case PairKind::elongated: {
                const Ellipsoid b(origin(), rotation(), elongated_axes(100.0));
                if (uniform(0, 1) < 0.5)
                    return {placed(elongated_axes(100.0), rotation(), b, uniform(-0.3, 0.3)), b,
                            kind};
                const glm::dvec3 inside =
                    b.sorted_axes() * (b.sorted_radii() * unit_vector() * uniform(0.0, 1.2));
                return {Ellipsoid(b.center() + inside, rotation(), elongated_axes(100.0)), b, kind};
            }
            case PairKind::crossing: {
                const glm::dquat qb = rotation();
                const Ellipsoid b(origin(), qb, elongated_axes(100.0));
                // a's long axis about orthogonal to b's: a quarter turn about b's middle axis,
                // tilted a little.
                const glm::dquat turn =
                    glm::angleAxis(1.5707963267948966 + uniform(-0.3, 0.3), b.sorted_axes()[1]);
                const glm::dquat qa =
                    glm::normalize(turn * glm::angleAxis(uniform(-0.3, 0.3), unit_vector()) * qb);
                const double reach = b.sorted_radii().y + b.sorted_radii().z;
                const glm::dvec3 offset = unit_vector() * uniform(0.0, reach);
                return {Ellipsoid(b.center() + offset, qa, elongated_axes(100.0)), b, kind};
            }
            case PairKind::coincident: {
                const glm::dvec3 c = origin();
                const glm::dvec3 ra = uniform(0, 1) < 0.5 ? car_axes() : elongated_axes(100.0);
                return {Ellipsoid(c, rotation(), ra), Ellipsoid(c, rotation(), car_axes()), kind};
            }
            case PairKind::identical: {
                const glm::dvec3 axes = uniform(0, 1) < 0.5 ? car_axes() : elongated_axes(100.0);
                const glm::dquat q = rotation();
                const Ellipsoid b(origin(), q, axes);
                const glm::dvec3 c = b.center() + unit_vector() * uniform(0.0, 2.2 * axes.x);
                return {Ellipsoid(c, q, axes), b, kind};
            }
            case PairKind::scaled: {
                const PairCase base =
                    make(uniform(0, 1) < 0.5 ? PairKind::car_like : PairKind::deep);
                const double s = log_uniform(1e-3, 1e3);
                return {
                    Ellipsoid(base.a.center() * s, base.a.orientation(), base.a.semi_axes() * s),
                    Ellipsoid(base.b.center() * s, base.b.orientation(), base.b.semi_axes() * s),
                    kind};
            }
            case PairKind::far: {
                const Ellipsoid b(unit_vector() * uniform(0.0, 1000.0), rotation(), car_axes());
                return {placed(car_axes(), rotation(), b, -log_uniform(10.0, 1e4)), b, kind};
            }
            default:
                break;
        }
        return make(PairKind::car_like);
    }

    /// c's pair one physics sub-step (10 ms / 40 = 0.25 ms) earlier, under a relative motion
    /// drawn for it: a moves against b at up to 20 m/s and turns about its centre at up to
    /// 3 rad/s, each in a uniform direction with a uniform magnitude. The earlier contact's
    /// normal is a warm start for c.
    PairCase earlier(const PairCase& c) {
        constexpr double kSubStep = 0.01 / 40.0;
        const glm::dvec3 velocity = unit_vector() * uniform(0.0, 20.0);
        const glm::dvec3 axis = unit_vector();
        const double rate = uniform(0.0, 3.0);
        const glm::dquat turn = glm::angleAxis(-rate * kSubStep, axis);
        const Ellipsoid a(c.a.center() - velocity * kSubStep,
                          glm::normalize(turn * c.a.orientation()), c.a.semi_axes());
        return {a, c.b, c.kind};
    }

    /// The support point of e in direction n (world).
    static glm::dvec3 support_point(const Ellipsoid& e, const glm::dvec3& n) {
        const glm::dvec3 local = n * e.sorted_axes();
        const glm::dvec3 r2 = e.sorted_radii() * e.sorted_radii();
        const double value = std::sqrt(glm::dot(r2 * local, local));
        return e.center() + e.sorted_axes() * (r2 * local / value);
    }

  private:
    glm::dvec3 origin() { return {uniform(-50.0, 50.0), uniform(-5.0, 5.0), uniform(-50.0, 50.0)}; }

    std::mt19937_64 rng_;
};

}  // namespace trackphys::test
