#include "trackphys/geometry/contact.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>
#include <glm/vector_relational.hpp>

#include "geometry/contact_extremes.hpp"
#include "geometry/contact_kernel.hpp"
#include "geometry/ellipsoid_roots.hpp"
#include "trackphys/math/types.hpp"

// The candidates and the certificate (docs/design.md#exact-ellipsoid-triangle-contact).
//
// In the sorted frame, E = {x : sum x_i^2 / r_i^2 <= 1} with support h(u) = ||D u|| and
// support point x(u) = D^2 u / h(u); sigma = min over unit u of g(u) = max_i u.q_i + h(u).
//
// Certificate. For any unit u let z(u) = x(-u) + g(u) u. Then u.z = max_i u.q_i, and z lies
// on the normal line of the surface point x(-u) (outward normal -u) at signed depth g(u).
// For every point z' of the triangle, g(u') >= u'.z' + h(u') for all u', whose minimum over
// u' is the signed depth of z' in E; so sigma >= depth(z'). If z(u) lies in the triangle and
// the critical point -u of z's distance is its closest point, i.e. the root t = -g h(u) of
// f is the largest one, which holds when t > -r_min^2, then depth(z) = g(u) and therefore
// sigma = g(u). Shallow contacts (depth < r_min^2 / h, 6 cm for a wheel) and every
// separated configuration are certified by the first candidate that passes; a vertex whose
// closest-point direction keeps it the top vertex is certified at any depth (z = q_i and
// the direction is its closest point by construction), and so is a face whose touching point
// lies far enough inside the triangle (big_face). Only the rest enumerate every local
// minimum. The deepest vertex, when it lies inside the ellipsoid, is tried before the face;
// after the face, the order follows where its touching point fell: beyond an edge, that edge
// (or the vertex past whose end it fell) comes first.
//
// Candidates (the minimiser of g has 3, 2 or 1 active vertices):
// - face: u = +-n; only the side facing the center can win, g(-n) >= g(n) when n.q <= 0;
// - edge (i, j): u on the circle orthogonal to e = q_j - q_i, where u.q_i = u.q_j and
//   h(B w) = sqrt(w^T B^T D^2 B w) for an orthonormal basis B of e's orthogonal plane: E's
//   shadow there is the ellipse with matrix M = B^T D^2 B, and the candidates are the
//   local minima of the 2-D problem for the point B^T q_i (point_ellipse);
// - vertex i: the local minima of u.q_i + h(u), i.e. of the offset from q_i to the surface
//   along the normal (point_ellipsoid), u = -normal.
// Each candidate's true g is >= sigma and the minimiser is among them.

namespace trackphys {
namespace detail {
namespace {

using glm::dvec3;

constexpr double kInfinity = std::numeric_limits<double>::infinity();

struct Problem {
    dvec3 r;   // radii
    dvec3 r2;  // squared radii
    double r_min2;
    std::array<double, 3> pole;    // (r_i - r_z)(r_i + r_z): offsets of the poles of f from -r_z^2
    dvec3 inv_r;                   // 1 / r_i
    std::array<double, 3> inv_r2;  // 1 / r_i^2
    const LocalTriangle* tri;

    double support(const dvec3& u) const { return std::sqrt(glm::dot(r2 * u, u)); }
    double top(const dvec3& u) const {
        return std::max({glm::dot(u, tri->q[0]), glm::dot(u, tri->q[1]), glm::dot(u, tri->q[2])});
    }
    /// True when the largest root condition t = -g h > -r_min^2 holds.
    bool closest_regime(double g, double h) const { return g * h < r_min2; }
};

/// The lowest candidate so far: g, its unit direction u and the ellipsoid's extreme point
/// x(-u) = -D^2 u / h(u) towards the triangle (kept for the contact point, and computed
/// by each candidate beside the normalisation of u rather than after it).
struct Best {
    double g = kInfinity;
    dvec3 u{0.0, 1.0, 0.0};
    dvec3 extreme{0.0, -1.0, 0.0};
    void offer(double value, const dvec3& u_candidate, const dvec3& extreme_candidate) {
        if (value < g) {
            g = value;
            u = u_candidate;
            extreme = extreme_candidate;
        }
    }
};

/// Whether a point p at level l = ||p / r|| (inverse radii inv, smallest radius r_small,
/// largest r_large) certainly has signed depth >= best, so that no candidate of it can win:
/// its depth is at least (1 - l) * r with r = r_small for l < 1, r_large otherwise, which
/// never exceeds r_small (so the level is only computed when best is below that). Tested
/// without a square root or a division: (1 - l) r >= best <=> l <= 1 - best / r, and for
/// l >= 0 that is 1 - best / r >= 0 and l^2 <= (1 - best / r)^2.
bool depth_at_least(double best, const dvec3& p, const dvec3& inv, double r_small, double inv_small,
                    double inv_large) {
    if (best > r_small) return false;
    const dvec3 scaled = p * inv;
    const double level2 = glm::dot(scaled, scaled);
    const double bound = 1.0 - best * (level2 < 1.0 ? inv_small : inv_large);
    return bound >= 0.0 && level2 <= bound * bound;
}

/// Edge (i, i+1) and its shadow ellipse: basis (b1, b2) of the plane orthogonal to the edge
/// rotated onto the shadow's axes, radii s1 >= s2, and the edge's 2-D point.
struct EdgeShadow {
    bool valid;
    dvec3 axis1, axis2;  // 3-D directions of the shadow's axes
    double s1, s2;
    double inv_s1, inv_s2;
    double px, py;         // the edge line's point in the shadow frame
    double closest_value;  // the closest candidate's edge value, once computed
};

EdgeShadow make_shadow(const Problem& pb, int i) {
    EdgeShadow s;
    s.valid = false;
    const dvec3& e = pb.tri->edge[i];
    const double length2 = glm::dot(e, e);
    if (!(length2 > 0.0)) return s;
    // b1: orthogonal to the edge and to the coordinate axis least aligned with it; b2 = e x b1
    // / |e|. The two square roots are independent.
    const dvec3 a = abs_each(e);
    const dvec3 b1_raw = a.x <= a.y && a.x <= a.z ? dvec3(0.0, e.z, -e.y)
                         : a.y <= a.z             ? dvec3(-e.z, 0.0, e.x)
                                                  : dvec3(e.y, -e.x, 0.0);
    const dvec3 b1 = b1_raw / std::sqrt(glm::dot(b1_raw, b1_raw));
    const dvec3 b2 = glm::cross(e, b1) / std::sqrt(length2);
    // M = B^T D^2 B and its eigenvectors (closed form for a symmetric 2x2).
    const double m00 = glm::dot(pb.r2 * b1, b1);
    const double m01 = glm::dot(pb.r2 * b1, b2);
    const double m11 = glm::dot(pb.r2 * b2, b2);
    const double mean = 0.5 * (m00 + m11);
    const double half_diff = 0.5 * (m00 - m11);
    const double radius = std::sqrt(half_diff * half_diff + m01 * m01);
    double vx = half_diff >= 0.0 ? half_diff + radius : m01;
    double vy = half_diff >= 0.0 ? m01 : radius - half_diff;
    const double vlen = std::sqrt(vx * vx + vy * vy);
    if (vlen > 0.0) {
        vx /= vlen;
        vy /= vlen;
    } else {
        vx = 1.0;
        vy = 0.0;
    }
    s.axis1 = vx * b1 + vy * b2;
    s.axis2 = -vy * b1 + vx * b2;
    s.s1 = std::sqrt(mean + radius);
    s.s2 = std::sqrt(std::max(mean - radius, 0.0));
    if (!(s.s2 > 0.0)) return s;
    s.inv_s1 = 1.0 / s.s1;
    s.inv_s2 = 1.0 / s.s2;
    s.px = glm::dot(s.axis1, pb.tri->q[i]);
    s.py = glm::dot(s.axis2, pb.tri->q[i]);
    s.valid = true;
    return s;
}

/// The closest point by the general solver (a coordinate of p is 0), in the form of
/// closest_direction_fast: a unit m.
template <int N>
ClosestDirection<N> closest_by_solver(const std::array<double, N>& r,
                                      const std::array<double, N>& p) {
    CriticalSolver<N> solver(r, p);
    CriticalPoints<N> found;
    solver.solve(CriticalSet::closest, found);
    const std::array<double, N>& n = found.points[0].n;
    double support2 = 0.0;
    for (int i = 0; i < N; ++i) support2 += r[i] * r[i] * n[i] * n[i];
    return {n, 1.0, support2, found.points[0].offset};
}

class Solver {
  public:
    Solver(const dvec3& radii, const LocalTriangle& tri) {
        pb_.r = radii;
        pb_.r2 = radii * radii;
        pb_.r_min2 = pb_.r2.z;
        pb_.tri = &tri;
    }

    [[gnu::always_inline]] LocalContact run() {
        const LocalTriangle& tri = *pb_.tri;
        // A vertex inside the ellipsoid is tried before the face: a vertex contact (a
        // triangle's corner pressed into the car) is then certified without the face, and a
        // shallow road contact, whose vertices are all far outside, pays only the test.
        const int inner = deepest_inner_vertex();
        if (inner >= 0 && try_first_vertex(inner)) return finish(ContactPath::vertex_certified);
        // Face, from the unnormalised area normal N: |N| and h(N) = |N| h(n) are independent
        // square roots, and u = sign N / |N| faces the center (g(-u) >= g(u)).
        // With r_z >= 2^-200 (unit scale, r_x in [1, 2)) or >= 2^-100 m (the fast path),
        // |N|^2 >= 2^-600 keeps |N|^2 and h(N)^2 >= r_z^2 |N|^2 normal numbers, so u is unit
        // and g exact. Below it the triangle lies within 2^-150 of one of its edges (its
        // height is |N| / longest edge, or every edge is below 2^-150), which moves sigma by
        // less than that: below an ulp of r_x at unit scale, far below the contract's 1e-9 m
        // on the fast path; the edges and vertices answer for it.
        const dvec3 area_normal = glm::cross(tri.edge[0], -tri.edge[2]);
        const double n2 = glm::dot(area_normal, area_normal);
        if (n2 >= 0x1p-600 && n2 < kInfinity) {
            const dvec3 r2n = pb_.r2 * area_normal;
            const double inv_length = 1.0 / std::sqrt(n2);
            const double hn = std::sqrt(glm::dot(r2n, area_normal));
            const double e0 = glm::dot(area_normal, tri.q[0]);
            const double e1 = glm::dot(area_normal, tri.q[1]);
            const double e2 = glm::dot(area_normal, tri.q[2]);
            const double sign = e0 + e1 + e2 > 0.0 ? -1.0 : 1.0;
            const double top = sign > 0.0 ? std::max({e0, e1, e2}) : -std::min({e0, e1, e2});
            const double spread = std::max({e0, e1, e2}) - std::min({e0, e1, e2});
            const dvec3 u = (sign * inv_length) * area_normal;
            const double g = (top + hn) * inv_length;
            const double h = hn * inv_length;
            const dvec3 extreme = (-sign / hn) * r2n;  // x(-u) = -D^2 u / h(u)
            const dvec3 z = extreme + g * u;
            // det(e_k, z - q_k, N) for the three edges; they sum to |N|^2 for any z.
            const double side0 = glm::dot(glm::cross(tri.edge[0], z - tri.q[0]), area_normal);
            const double side1 = glm::dot(glm::cross(tri.edge[1], z - tri.q[1]), area_normal);
            const double side2 = n2 - side0 - side1;
            // The vertices must lie on the face plane to rounding: a sliver's normal may be
            // too inaccurate for the certificate, and then the edges decide. Collinear
            // vertices pass that test with a normal of pure rounding noise (and certified a
            // wrong face 1.4e-4 m off: found by fuzz_contact), so the angle between the edges
            // must also be clear of rounding: sin > 1e-10, n2 = |e0|^2 |e2|^2 sin^2.
            const double scale = pb_.r.x + tri.extent;
            const double sliver =
                1e-20 * glm::dot(tri.edge[0], tri.edge[0]) * glm::dot(tri.edge[2], tri.edge[2]);
            const bool inside = side0 >= 0.0 && side1 >= 0.0 && side2 >= 0.0 &&
                                spread * inv_length <= 1e-14 * scale && n2 > sliver;
            if (inside & pb_.closest_regime(g, h))
                return {g, u, extreme + 0.5 * g * u, ContactPath::face_certified, 0};
            // Kept only now: stores on the certified path would cost more than the math.
            if (inner < 0) begin_search();
            best_.offer(g, u, extreme);
            side_[0] = side0;
            side_[1] = side1;
            side_[2] = side2;
            face_touch_ = z;
            if (inside && big_face(n2)) return finish(ContactPath::face_certified);
            return edges_and_vertices(inner);
        }
        if (inner < 0) begin_search();
        return edges_and_vertices(inner);
    }

  private:
    /// The state of the search past the face, set up only when the face did not answer.
    void begin_search() {
        const dvec3& r = pb_.r;
        for (int i = 0; i < 3; ++i) pb_.pole[i] = (r[i] - r.z) * (r[i] + r.z);
        pb_.inv_r = 1.0 / r;
        for (int i = 0; i < 3; ++i) pb_.inv_r2[i] = pb_.inv_r[i] * pb_.inv_r[i];
        best_ = Best{};
        iterations_ = 0;
        face_touch_ = dvec3(0.0);
        side_[0] = side_[1] = side_[2] = 0.0;
    }

    /// The vertex deepest in level l_i^2 = sum_k q_ik^2 / r_k^2 when it lies inside (l < 1),
    /// else -1. Compared as l_i^2 r_x^2 r_y^2 r_z^2 = sum_k q_ik^2 prod_{j != k} r_j^2, so that
    /// every contact pays no division for it.
    int deepest_inner_vertex() const {
        const dvec3& r2 = pb_.r2;
        const dvec3 weight(r2.y * r2.z, r2.x * r2.z, r2.x * r2.y);
        const LocalTriangle& tri = *pb_.tri;
        double level[3];
        for (int i = 0; i < 3; ++i) level[i] = glm::dot(tri.q[i] * tri.q[i], weight);
        const int lower = level[1] < level[0] ? 1 : 0;
        const int deepest = level[2] < level[lower] ? 2 : lower;
        return level[deepest] < r2.x * weight.x ? deepest : -1;
    }

    /// The search begun at vertex i (out of line, as edges_and_vertices).
    [[gnu::noinline]] bool try_first_vertex(int i) {
        begin_search();
        return try_vertex(i);
    }

    /// Everything after the face, out of line so that the face path stays small and inlined.
    /// tried: a vertex already tried (deepest_inner_vertex), or -1.
    [[gnu::noinline]] LocalContact edges_and_vertices(int tried) {
        // Edges and vertices by their closest-point candidates, the ones the face's touching
        // point fell beyond first.
        int order[6];
        feature_order(order);
        for (const int feature : order) {
            if (tried >= 0 && feature == 3 + tried) continue;
            if (feature < 3 ? try_edge(feature) : try_vertex(feature - 3))
                return finish(feature < 3 ? ContactPath::edge_certified
                                          : ContactPath::vertex_certified);
        }

        // Deep: every other local minimum of every edge and vertex that can still win.
        for (int i = 0; i < 3; ++i) other_edge_minima(i);
        for (int i = 0; i < 3; ++i) other_vertex_minima(i);
        return finish(ContactPath::enumerated);
    }

    LocalContact finish(ContactPath path) const {
        // The ellipsoid's extreme point towards the triangle, x(-u), moved by half the depth.
        const dvec3 point = 0.5 * best_.g * best_.u + best_.extreme;
        return {best_.g, best_.u, point, path, iterations_};
    }

    void feature_order(int (&order)[6]) const {
        // side_[k] < 0: the face's touching point is beyond edge k (from q_k to q_{k+1}); beyond
        // one of its ends, the vertex there is the likely winner.
        int n = 0;
        int outside = -1;
        int count_outside = 0;
        for (int k = 0; k < 3; ++k)
            if (side_[k] < 0.0) {
                ++count_outside;
                outside = k;
            }
        if (count_outside == 1) {
            const dvec3& e = pb_.tri->edge[outside];
            const double along = glm::dot(face_touch_ - pb_.tri->q[outside], e);
            const int start = 3 + outside;
            const int end = 3 + (outside + 1) % 3;
            if (along < 0.0) {
                order[n++] = start;
                order[n++] = outside;
            } else if (along > glm::dot(e, e)) {
                order[n++] = end;
                order[n++] = outside;
            } else {
                order[n++] = outside;
                order[n++] = start;
                order[n++] = end;
            }
        } else if (count_outside == 2) {
            // Beyond two edges: the vertex they share first.
            const int inside = side_[0] >= 0.0 ? 0 : side_[1] >= 0.0 ? 1 : 2;
            const int vertex = (inside + 2) % 3;
            order[n++] = 3 + vertex;
            order[n++] = vertex;
            order[n++] = (vertex + 2) % 3;
        }
        for (int f = 0; f < 6; ++f)
            if (std::find(order, order + n, f) == order + n) order[n++] = f;
    }

    bool try_edge(int i) {
        shadow_[i] = make_shadow(pb_, i);
        EdgeShadow& s = shadow_[i];
        s.closest_value = kInfinity;
        if (!s.valid || cannot_win(s)) return false;
        const double pole = (s.s1 - s.s2) * (s.s1 + s.s2);
        const ClosestDirection<2> d =
            s.py != 0.0 ? closest_direction_fast<2>({s.s1, s.s2}, {pole, 0.0},
                                                    {s.inv_s1 * s.inv_s1, s.inv_s2 * s.inv_s2},
                                                    {s.px, s.py}, iterations_)
                        : closest_by_solver<2>({s.s1, s.s2}, {s.px, s.py});
        // The shadow's axes are orthonormal, so the 3-D direction has the 2-D length, and the
        // shadow's support is the ellipsoid's for directions orthogonal to the edge.
        const Candidate c = candidate(-(d.m[0] * s.axis1 + d.m[1] * s.axis2), d);
        s.closest_value = -d.offset_times_length * c.inv_length;
        best_.offer(c.g, c.u, c.extreme);
        if (c.dots[(i + 2) % 3] > std::max(c.dots[i], c.dots[(i + 1) % 3])) return false;
        const LocalTriangle& tri = *pb_.tri;
        const dvec3 z = c.g * c.u + c.extreme;
        const double along = glm::dot(z - tri.q[i], tri.edge[i]);
        return along >= 0.0 && along <= glm::dot(tri.edge[i], tri.edge[i]) &&
               pb_.closest_regime(c.g, c.h);
    }

    /// A closest-point candidate given its push direction unnormalised, m = |m| u, and the
    /// closest point it came from (|m|^2 and h(m)^2): |m| and h(m) = |m| h(u) are independent
    /// square roots, g = (max_i m.q_i + h(m)) / |m|, the extreme point x(-u) = -D^2 m / h(m)
    /// needs no |m|, and dots keeps m.q_i (their order is that of u.q_i).
    struct Candidate {
        dvec3 u, extreme;
        double g, h, inv_length;
        dvec3 dots;
    };

    template <int N>
    Candidate candidate(const dvec3& m, const ClosestDirection<N>& d) const {
        const LocalTriangle& tri = *pb_.tri;
        const double hm = std::sqrt(d.support2);
        const double inv_length = 1.0 / std::sqrt(d.norm2);
        Candidate c;
        c.extreme = pb_.r2 * m * (-1.0 / hm);
        c.dots = dvec3(glm::dot(m, tri.q[0]), glm::dot(m, tri.q[1]), glm::dot(m, tri.q[2]));
        c.g = (std::max({c.dots.x, c.dots.y, c.dots.z}) + hm) * inv_length;
        c.h = hm * inv_length;
        c.u = m * inv_length;
        c.inv_length = inv_length;
        return c;
    }

    /// Offers a unit direction found by the deep enumeration.
    void offer_direction(const dvec3& u) {
        const double h = pb_.support(u);
        best_.offer(pb_.top(u) + h, u, pb_.r2 * u * (-1.0 / h));
    }

    /// The deep face certificate: the face's touching point z lies at least
    /// R = g + |z| + r_max from every edge line. Then for u = c n + s t (t tangent, s >= 0),
    /// g(u) >= u.z + R s + h(u) over the disk of radius R around z. For c >= 0, u.z + h(u) is
    /// convex and 1-homogeneous with gradient x(n) + z = g n at n, so g(u) >= g c + R s >= g
    /// (1 - c <= s, R >= g). For c < 0, the plane offset n.z <= 0 and h(u) >= |c| h(n) -
    /// s r_max give g(u) >= (1 - s)(h(n) - n.z) + s (R - |z| - r_max) >= h(n) + n.z = g. So n
    /// minimises g at any depth: a wheel pressed deep into a large road triangle.
    /// side_k = |N| |e_k| times z's distance from edge line k. The distance is formed by
    /// dividing (a length^4 over a length^3), not by comparing squares: those are 8th powers
    /// of lengths, which underflow to 0 = 0 at 1e-54 m (and certified a wrong face there).
    /// Reads the face's stored best_, face_touch_ and side_; n2 = |N|^2.
    [[gnu::noinline]] bool big_face(double n2) const {
        const double g = best_.g;
        if (!(g > 0.0)) return false;
        const double r = g + glm::length(face_touch_) + pb_.r.x;
        const double inv_length = 1.0 / std::sqrt(n2);
        const LocalTriangle& tri = *pb_.tri;
        for (int k = 0; k < 3; ++k)
            if (side_[k] * inv_length < r * glm::length(tri.edge[k])) return false;
        return true;
    }

    /// No direction orthogonal to the edge gives g below the 2-D depth of its point.
    bool cannot_win(const EdgeShadow& s) const {
        return depth_at_least(best_.g, dvec3(s.px, s.py, 0.0), dvec3(s.inv_s1, s.inv_s2, 0.0), s.s2,
                              s.inv_s2, s.inv_s1);
    }

    bool try_vertex(int i) {
        const dvec3& q = pb_.tri->q[i];
        vertex_closest_[i] = kInfinity;
        if (depth_at_least(best_.g, q, pb_.inv_r, pb_.r.z, pb_.inv_r.z, pb_.inv_r.x)) return false;
        const std::array<double, 3> r = {pb_.r.x, pb_.r.y, pb_.r.z};
        const ClosestDirection<3> d =
            q.z != 0.0
                ? closest_direction_fast<3>(r, pb_.pole, pb_.inv_r2, {q.x, q.y, q.z}, iterations_)
                : closest_by_solver<3>(r, {q.x, q.y, q.z});
        const Candidate c = candidate(-dvec3(d.m[0], d.m[1], d.m[2]), d);
        vertex_closest_[i] = -d.offset_times_length * c.inv_length;
        best_.offer(c.g, c.u, c.extreme);
        // u comes from q's closest point, so g = depth(q) when the vertex is active: q is the
        // deepest point of the triangle and sigma = g at any depth.
        return c.dots[i] >= std::max(c.dots[(i + 1) % 3], c.dots[(i + 2) % 3]);
    }

    void other_edge_minima(int i) {
        const EdgeShadow& s = shadow_[i];
        // Every local minimum of the edge's function is >= its global one, and >= |p_y| (see
        // other_vertex_minima).
        if (!s.valid || std::max(s.closest_value, std::abs(s.py)) >= best_.g || cannot_win(s))
            return;
        if (s.py != 0.0) {
            std::array<double, 2> n;
            const double pole = (s.s1 - s.s2) * (s.s1 + s.s2);
            if (other_minimum_normal_fast<2>({s.s1, s.s2}, {pole, 0.0}, {s.px, s.py}, n,
                                             iterations_)) {
                offer_direction(-(n[0] * s.axis1 + n[1] * s.axis2));
            }
            return;
        }
        CriticalSolver<2> solver({s.s1, s.s2}, {s.px, s.py});
        CriticalPoints<2> found;
        solver.solve(CriticalSet::other_minima, found);
        for (int k = 0; k < found.count; ++k) {
            const CriticalPoint<2>& cp = found.points[k];
            offer_direction(-(cp.n[0] * s.axis1 + cp.n[1] * s.axis2));
        }
    }

    void other_vertex_minima(int i) {
        // The other minima lie left of the smallest radius' pole, t < -r_z^2, where
        // x_z = r_z^2 q_z / (r_z^2 + t) has the sign opposite to q_z and lambda = -t |D^-2 x| > 0
        // is |x - q| >= |x_z - q_z| >= |q_z|; and every local minimum is >= the global one.
        const dvec3& q = pb_.tri->q[i];
        if (std::max(vertex_closest_[i], std::abs(q.z)) >= best_.g) return;
        if (q.z != 0.0) {
            std::array<double, 3> n;
            if (other_minimum_normal_fast<3>({pb_.r.x, pb_.r.y, pb_.r.z}, pb_.pole, {q.x, q.y, q.z},
                                             n, iterations_)) {
                offer_direction(dvec3(-n[0], -n[1], -n[2]));
            }
            return;
        }
        CriticalSolver<3> solver({pb_.r.x, pb_.r.y, pb_.r.z}, {q.x, q.y, q.z});
        CriticalPoints<3> found;
        solver.solve(CriticalSet::other_minima, found);
        for (int k = 0; k < found.count; ++k) {
            const CriticalPoint<3>& cp = found.points[k];
            offer_direction(dvec3(-cp.n[0], -cp.n[1], -cp.n[2]));
        }
    }

    Problem pb_;
    // Set by begin_search().
    Best best_;
    int iterations_;
    dvec3 face_touch_;
    double side_[3];
    // Filled by try_edge and try_vertex for every feature before the deep enumeration reads them.
    EdgeShadow shadow_[3];
    double vertex_closest_[3];
};

}  // namespace

LocalContact contact_in_sorted_frame(const glm::dvec3& radii, const LocalTriangle& triangle) {
    return Solver(radii, triangle).run();
}

namespace {

/// The same, inlined into the public entry so that the shallow face path keeps the triangle
/// in registers.
[[gnu::always_inline]] inline LocalContact solve_inline(const glm::dvec3& radii,
                                                        const LocalTriangle& triangle) {
    return Solver(radii, triangle).run();
}

}  // namespace

}  // namespace detail

namespace {

bool finite_triangle(const Triangle& t) {
    return is_finite(t[0]) && is_finite(t[1]) && is_finite(t[2]);
}

/// a < b in lexicographic order, without branches (the order of road triangles' vertices is
/// random, so branches here would mispredict).
bool lexicographic_less(const glm::dvec3& a, const glm::dvec3& b) {
    return (a.x < b.x) | ((a.x == b.x) & ((a.y < b.y) | ((a.y == b.y) & (a.z < b.z))));
}

/// The vertex order that sorts the triangle lexicographically, ties keeping the given order
/// (a stable three-element sorting network): sigma does not depend on the order or winding,
/// and solving in a canonical order makes the rounded result bit-identical for every
/// permutation. Built from swaps, it is a permutation even when a NaN makes the comparisons
/// inconsistent (ranks counted from them could repeat and index past the triangle): the NaN
/// vertex still reaches the extent check below, which sends it to the -infinity answer.
/// Selects rather than branches (conditional moves), like lexicographic_less.
std::array<int, 3> canonical_order(const Triangle& t) {
    const bool swap01 = lexicographic_less(t[1], t[0]);
    const int low = swap01 ? 1 : 0, high = swap01 ? 0 : 1;
    const bool swap12 = lexicographic_less(t[2], t[high]);
    const int middle = swap12 ? 2 : high, top = swap12 ? high : 2;
    const bool swap01_again = lexicographic_less(t[middle], t[low]);
    return {swap01_again ? middle : low, swap01_again ? low : middle, top};
}

/// The triangle's vertices in canonical order.
std::array<glm::dvec3, 3> canonical_vertices(const Triangle& t, const std::array<int, 3>& order) {
    return {t[order[0]], t[order[1]], t[order[2]]};
}

/// Sets the coordinates below negligible to zero (see ellipsoid_triangle_contact).
[[gnu::noinline]] void flush_negligible(std::array<glm::dvec3, 3>& q, double negligible) {
    for (glm::dvec3& v : q)
        v *= glm::dvec3(glm::greaterThanEqual(abs_each(v), glm::dvec3(negligible)));
}

}  // namespace

Contact ellipsoid_triangle_contact(const Ellipsoid& ellipsoid, const Triangle& triangle) {
    const glm::dvec3& c = ellipsoid.center();
    const glm::dmat3& axes = ellipsoid.sorted_axes();
    const glm::dvec3& radii = ellipsoid.sorted_radii();
    const std::array<int, 3> order = canonical_order(triangle);
    detail::LocalTriangle local;
    for (int k = 0; k < 3; ++k)  // row vector * M = M^T * column
        local.q[k] = (triangle[order[static_cast<std::size_t>(k)]] - c) * axes;
    // The fast solver needs every product it forms, up to the sixth power of a length
    // (h(N)^2 = |D N|^2 for the area normal N), to be a normal number: radii within
    // [2^-100, 2^100], the smallest radius within 2^200 of the largest and of the triangle's
    // extent, vertices within 2^100 of the center, as every car and track is (edges are at
    // most twice the largest |q|); tiny vertex offsets are flushed below. fuzz_contact found
    // each bound the hard way: 1e262 m and 1e79 m radii gave an infinite depth or a NaN
    // normal, 1e-76 m radii a normal 2e-8 off unit, a 1e114 radii ratio an infinite depth, a
    // 1e-57 m sphere under a 1e5 m triangle a normal 5e-7 off unit; and the power-of-two
    // scaling test a wrong depth for a car scaled by 2^-179 or 2^170 (sixth powers). The
    // careful path solves at unit scale (rescaled_contact) and raises radii below 2^-200
    // of the largest to it (or treats the ellipsoid as a point), which moves sigma by less
    // than that. The sum also catches non-finite input (NaN and infinity propagate).
    const std::array<glm::dvec3, 3> abs_q = {abs_each(local.q[0]), abs_each(local.q[1]),
                                             abs_each(local.q[2])};
    const glm::dvec3 sum = abs_q[0] + abs_q[1] + abs_q[2];
    local.extent = sum.x + sum.y + sum.z;
    if (!(local.extent < 0x1p100) || radii.z < 0x1p-100 || !(radii.x < 0x1p100) ||
        radii.z < std::max(radii.x, local.extent) * 0x1p-200) {
        if (!finite_triangle(triangle))
            return {-std::numeric_limits<double>::infinity(), glm::dvec3(0.0, 1.0, 0.0), c};
        return detail::rescaled_contact(ellipsoid, canonical_vertices(triangle, order));
    }
    // Offsets below 2^-200 of the configuration are flushed to zero: moving a vertex by that
    // little moves sigma by less, while a subnormal one (1e-311 m from the center of a 32 m
    // ellipsoid, found by fuzz_contact) made the solver miss the minimum by 1.3 cm, and one
    // beside 1e-76 m radii gave an infinite depth. Tested on the smallest offset first: a
    // car's coordinates are never that small (nor, in a rotated frame, exactly 0), and a
    // mask on every coordinate would cost the shallow road contact, the common case.
    const double negligible = std::max(local.extent, radii.x) * 0x1p-200;
    const glm::dvec3 smallest = glm::min(glm::min(abs_q[0], abs_q[1]), abs_q[2]);
    if (std::min({smallest.x, smallest.y, smallest.z}) < negligible) [[unlikely]]
        flush_negligible(local.q, negligible);
    for (int i = 0; i < 3; ++i) local.edge[i] = local.q[(i + 1) % 3] - local.q[i];
    const detail::LocalContact solved = detail::solve_inline(radii, local);
    return {solved.depth, axes * solved.u, c + axes * solved.point};
}

}  // namespace trackphys
