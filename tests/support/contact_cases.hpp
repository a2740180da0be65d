#pragma once

// Ellipsoid-triangle configurations for the contact tests and the benchmark: wheel- and
// body-sized ellipsoids against road faces, edges and vertices at shallow depth, deep
// contacts, misses, and adversarial triangles (slivers, huge, tiny, through the center,
// edge-on, segments and points). Deterministic for a given seed.

#include <array>
#include <cmath>
#include <random>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

#include "trackphys/geometry/ellipsoid.hpp"
#include "trackphys/geometry/triangle.hpp"

namespace trackphys::test {

enum class ContactKind {
    road,     ///< face-dominant road contact, depth in (0, 5 cm)
    edge,     ///< an edge touches, depth in (-5 cm, 5 cm)
    vertex,   ///< a vertex touches, depth in (-5 cm, 5 cm)
    deep,     ///< triangle deep inside or through the ellipsoid
    miss,     ///< apart by 1 mm to 20 m
    random,   ///< vertices anywhere within 2 radii of the center
    sliver,   ///< one vertex 1e-9..1e-3 of the length off the opposite edge
    huge,     ///< 1e3..1e6 m triangle near the ellipsoid
    tiny,     ///< 1e-9..1e-4 m triangle near the surface
    segment,  ///< collinear vertices
    point,    ///< coincident vertices (two or three)
    through_center,
    edge_on,  ///< the triangle's plane contains the push direction
    count
};

inline const char* contact_kind_name(ContactKind k) {
    static const char* names[] = {"road",   "edge",           "vertex", "deep", "miss",
                                  "random", "sliver",         "huge",   "tiny", "segment",
                                  "point",  "through_center", "edge_on"};
    return names[static_cast<int>(k)];
}

struct ContactCase {
    Ellipsoid ellipsoid;
    Triangle triangle;
    ContactKind kind;
};

class ContactCaseGenerator {
  public:
    /// wheel_and_body: only the car's two shapes (the benchmark); else also random radii.
    explicit ContactCaseGenerator(std::uint64_t seed, bool wheel_and_body = false)
        : rng_(seed), wheel_and_body_(wheel_and_body) {}

    /// A case of the given kind with a wheel, a body or a random ellipsoid.
    ContactCase make(ContactKind kind) {
        const Ellipsoid e = ellipsoid();
        return {e, triangle(e, kind), kind};
    }

    /// Any kind, adversarial ones included.
    ContactCase any() {
        return make(static_cast<ContactKind>(pick(static_cast<int>(ContactKind::count))));
    }

    /// The benchmark's hard mix: 75% overlapping (road, edge, vertex, deep), 25% apart.
    ContactCase hard_mix() {
        const double x = uniform(0, 1);
        if (x < 0.25) return make(ContactKind::miss);
        if (x < 0.45) return make(ContactKind::road);
        if (x < 0.6) return make(ContactKind::edge, true);
        if (x < 0.75) return make(ContactKind::vertex, true);
        return make(ContactKind::deep);
    }

    ContactCase make(ContactKind kind, bool overlapping) {
        overlapping_ = overlapping;
        ContactCase c = make(kind);
        overlapping_ = false;
        return c;
    }

    double uniform(double lo, double hi) {
        return std::uniform_real_distribution<double>(lo, hi)(rng_);
    }
    int pick(int n) { return std::uniform_int_distribution<int>(0, n - 1)(rng_); }
    glm::dvec3 direction() {
        glm::dvec3 d(normal_(rng_), normal_(rng_), normal_(rng_));
        return glm::normalize(d);
    }
    glm::dquat rotation() {
        return glm::normalize(
            glm::dquat(normal_(rng_), normal_(rng_), normal_(rng_), normal_(rng_)));
    }

  private:
    Ellipsoid ellipsoid() {
        glm::dvec3 axes;
        switch (pick(wheel_and_body_ ? 2 : 4)) {
            case 0:
                axes = {0.15, 0.35, 0.35};
                break;  // wheel, axle along local x
            case 1:
                axes = {1.0, 0.5, 2.0};
                break;  // body
            case 2:
                axes = glm::dvec3(uniform(0.05, 3.0));
                axes.y *= 1 + uniform(-1e-9, 1e-9);
                break;
            default:
                axes = {uniform(0.05, 3.0), uniform(0.05, 3.0), uniform(0.05, 3.0)};
                break;
        }
        const glm::dvec3 center(uniform(-50, 50), uniform(-5, 5), uniform(-50, 50));
        return Ellipsoid(center, rotation(), axes);
    }

    /// The ellipsoid's extreme point in world direction d.
    static glm::dvec3 support_point(const Ellipsoid& e, const glm::dvec3& d) {
        const glm::dvec3 local = glm::transpose(e.sorted_axes()) * d;
        const glm::dvec3 r2 = e.sorted_radii() * e.sorted_radii();
        const glm::dvec3 x = r2 * local / std::sqrt(glm::dot(r2 * local, local));
        return e.center() + e.sorted_axes() * x;
    }

    /// Two unit vectors completing u to an orthonormal frame.
    static void frame(const glm::dvec3& u, glm::dvec3& a, glm::dvec3& b) {
        const glm::dvec3 helper = std::abs(u.x) < 0.6 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
        a = glm::normalize(glm::cross(u, helper));
        b = glm::cross(u, a);
    }

    double shallow_depth() { return overlapping_ ? uniform(0.0, 0.05) : uniform(-0.05, 0.05); }

    Triangle triangle(const Ellipsoid& e, ContactKind kind) {
        const double r0 = e.sorted_radii().x;
        const glm::dvec3 c = e.center();
        // Push direction u; mostly "up" for roads.
        glm::dvec3 u = kind == ContactKind::road
                           ? glm::normalize(glm::dvec3(uniform(-0.3, 0.3), 1.0, uniform(-0.3, 0.3)))
                           : direction();
        glm::dvec3 a, b;
        frame(u, a, b);
        // The touching point for a contact of the given depth along u.
        const auto touch = [&](double depth) { return support_point(e, -u) + depth * u; };
        const auto around = [&](const glm::dvec3& z, double size) {
            // A triangle in the plane orthogonal to u that contains z.
            const double t0 = uniform(0, 6.283185307179586);
            std::array<glm::dvec3, 3> v;
            for (int i = 0; i < 3; ++i) {
                const double t = t0 + 2.0943951023931953 * i + uniform(-0.5, 0.5);
                v[i] = z + size * uniform(0.3, 1.0) * (std::cos(t) * a + std::sin(t) * b);
            }
            return Triangle(v[0], v[1], v[2]);
        };
        switch (kind) {
            case ContactKind::road:
                return around(touch(uniform(0.0, 0.05)), uniform(1.0, 10.0));
            case ContactKind::edge: {
                const glm::dvec3 z = touch(shallow_depth());
                const double l = uniform(0.5, 5.0);
                const double s = uniform(0.1, 0.9);
                return Triangle(z - s * l * a, z + (1 - s) * l * a,
                                z + uniform(-1, 1) * a + uniform(0.5, 3) * b - uniform(0.2, 2) * u);
            }
            case ContactKind::vertex: {
                const glm::dvec3 z = touch(shallow_depth());
                const double t = uniform(0, 6.283185307179586);
                const glm::dvec3 w1 = std::cos(t) * a + std::sin(t) * b;
                const glm::dvec3 w2 = std::cos(t + 1) * a + std::sin(t + 1) * b;
                return Triangle(z, z + uniform(0.5, 3) * w1 - uniform(0.3, 2) * u,
                                z + uniform(0.5, 3) * w2 - uniform(0.3, 2) * u);
            }
            case ContactKind::deep: {
                if (pick(2))
                    return around(touch(uniform(0.3, 1.5) * e.sorted_radii().z + 0.05),
                                  uniform(0.5, 5.0));
                std::array<glm::dvec3, 3> v;
                for (auto& x : v) x = c + r0 * uniform(0.0, 0.8) * direction();
                return Triangle(v[0], v[1], v[2]);
            }
            case ContactKind::miss: {
                const double gap = std::pow(10.0, uniform(-3, 1.3));
                if (pick(2)) return around(touch(-gap), uniform(0.5, 10.0));
                const glm::dvec3 z = touch(-gap);
                return Triangle(z, z + uniform(0.2, 3) * a - uniform(0, 1) * u,
                                z + uniform(0.2, 3) * b - uniform(0, 1) * u);
            }
            case ContactKind::random: {
                std::array<glm::dvec3, 3> v;
                for (auto& x : v) x = c + r0 * uniform(0.0, 2.0) * direction();
                return Triangle(v[0], v[1], v[2]);
            }
            case ContactKind::sliver: {
                const glm::dvec3 z = touch(uniform(-0.1, 0.3));
                const double l = uniform(0.5, 5.0);
                const glm::dvec3 p0 = z - uniform(0, 1) * l * a, p1 = p0 + l * a;
                const double off = l * std::pow(10.0, uniform(-9, -3));
                return Triangle(p0, p1, p0 + uniform(-0.5, 1.5) * l * a + off * (pick(2) ? b : u));
            }
            case ContactKind::huge:
                return around(touch(uniform(-0.1, 0.3)), std::pow(10.0, uniform(3, 6)));
            case ContactKind::tiny:
                return around(touch(uniform(-0.01, 0.01)), std::pow(10.0, uniform(-9, -4)));
            case ContactKind::segment: {
                const glm::dvec3 z = touch(uniform(-0.1, 0.5));
                const glm::dvec3 d = direction();
                const double s0 = uniform(-2, 0), s1 = uniform(0, 2);
                return Triangle(z + s0 * d, z + s1 * d, z + uniform(s0, s1) * d);
            }
            case ContactKind::point: {
                const glm::dvec3 z =
                    pick(2) ? touch(uniform(-0.1, 0.5)) : c + r0 * uniform(0, 1) * direction();
                if (pick(2)) return Triangle(z, z, z);
                const glm::dvec3 w = z + uniform(0.1, 2) * direction();
                return pick(2) ? Triangle(z, w, z) : Triangle(z, z, w);
            }
            case ContactKind::through_center: {
                // The ellipsoid's center on the triangle (sometimes exactly on a vertex).
                std::array<glm::dvec3, 3> v;
                const double t0 = uniform(0, 6.283185307179586);
                for (int i = 0; i < 3; ++i) {
                    const double t = t0 + 2.0943951023931953 * i;
                    v[i] = c + uniform(0.05, 3.0) * (std::cos(t) * a + std::sin(t) * b);
                }
                if (pick(4) == 0) v[0] = c;
                return Triangle(v[0], v[1], v[2]);
            }
            case ContactKind::edge_on: {
                const glm::dvec3 z = touch(uniform(-0.1, 0.3));
                return Triangle(z, z - uniform(0.2, 3) * u + uniform(-1, 1) * a,
                                z - uniform(0.2, 3) * u + uniform(-1, 1) * a);
            }
            case ContactKind::count:
                break;
        }
        return Triangle(c, c, c);
    }

    std::mt19937_64 rng_;
    std::normal_distribution<double> normal_;
    bool wheel_and_body_;
    bool overlapping_ = false;
};

}  // namespace trackphys::test
