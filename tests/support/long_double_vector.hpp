#pragma once
// The references' arithmetic: three long doubles and the few operations the long-double
// references (contact, ellipsoid pair) are written in, plus the downhill step on the unit
// sphere that both refine their minimisers with.

#include <cmath>

namespace trackphys::test {

using R = long double;

struct V3 {
    R x = 0, y = 0, z = 0;
    R operator[](int i) const { return i == 0 ? x : i == 1 ? y : z; }
};
inline V3 operator+(V3 a, V3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline V3 operator-(V3 a, V3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline V3 operator*(V3 a, R s) { return {a.x * s, a.y * s, a.z * s}; }
inline V3 operator*(R s, V3 a) { return a * s; }
inline R dot(V3 a, V3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline V3 cross(V3 a, V3 b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline R norm(V3 a) { return std::sqrt(dot(a, a)); }
inline V3 unit(V3 a) { return a * (1 / norm(a)); }

/// Moves the unit vector u to unit(u + t1 s1 + t2 s2), halving the step (at most `halvings`
/// times) until f does not rise there. Returns whether u changed: false ends a descent.
template <class F>
bool step_downhill_on_sphere(V3& u, V3 t1, V3 t2, R s1, R s2, F f, int halvings) {
    const R now = f(u);
    for (int halving = 0; halving < halvings; ++halving) {
        const V3 next = unit(u + t1 * s1 + t2 * s2);
        if (f(next) <= now) {
            const bool moved = !(next.x == u.x && next.y == u.y && next.z == u.z);
            u = next;
            return moved;
        }
        s1 /= 2;
        s2 /= 2;
    }
    return false;
}

}  // namespace trackphys::test
