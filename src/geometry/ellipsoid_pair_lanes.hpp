#pragma once

#include <array>

#include "geometry/ellipsoid_pair_kernel.hpp"
#include "geometry/lane_ops.hpp"

namespace trackphys::detail {

/// solve_pair's common path for N frames at once (N = 2 or 4), bit for bit: each lane runs
/// the scalar IEEE operations of ellipsoid_pair_kernel.cpp in their order (first_guess,
/// PairFunction::at, definite_step and stepped, descend, the two certificates; the build
/// contracts no multiply-add), so a lane that stays on the path gives solve_pair's bits. A
/// lane that leaves it (a Hessian not definite, a step beyond the trust radius, a failed
/// decrease test, a first guess the scalar code replaces by the centre line, the descent's
/// cap, no certificate) is dropped, and its frame is solved again by
/// solve_pair. The lanes run until every lane is finished or dropped. Every member is forced
/// inline, as LaneOps' are: four lanes run inside an AVX2 caller (ellipsoid_pair_lanes.cpp).
template <int N>
class PairLanes {
    using Ops = LaneOps<N>;
    using Lanes = typename Ops::Lanes;
    using Mask = typename Ops::Mask;
    using Lanes3 = typename Ops::Lanes3;

  public:
    /// Frame k in lane k; solutions[k] is set where bit k of the result is.
    [[gnu::always_inline]] explicit PairLanes(const PairFrame* const (&frames)[N]) {
        const Lanes3 ra = Ops::gather(frames, &PairFrame::ra);
        rb_ = Ops::gather(frames, &PairFrame::rb);
        d_ = Ops::gather(frames, &PairFrame::d);
        d_in_b_ = Ops::gather(frames, &PairFrame::d_in_b);
        for (int j = 0; j < 3; ++j)
            for (int k = 0; k < N; ++k) {
                const glm::dvec3& column = frames[k]->b_axes[j];
                b_axes_[j].x[k] = column.x;
                b_axes_[j].y[k] = column.y;
                b_axes_[j].z[k] = column.z;
            }
        ra2_ = times(ra, ra);
        rb2_ = times(rb_, rb_);
        mb_ = {support_entry(0, 0), support_entry(1, 1), support_entry(2, 2),
               support_entry(0, 1), support_entry(0, 2), support_entry(1, 2)};
    }

    /// Bit k where lane k stayed on the common path, with its solution in solutions[k].
    [[gnu::always_inline]] unsigned solve(PairSolution* const (&solutions)[N]) const {
        Lanes3 guess;
        Mask dropped = ~first_guess(guess);
        Sample s = at(guess);
        Lanes evaluations = Ops::every(1.0);
        // descend's loop on the path kept: definite steps, taken where they decrease h or
        // lie in the quadratic region, until a step is short enough to end on.
        Mask active = ~dropped, done{};
        Sample result = s;
        Lanes previous2 = Ops::every(0.0);
        for (int iteration = 0; iteration < kDescentCap && Ops::bits(active) != 0; ++iteration) {
            const Lanes scale = s.a + s.b + Ops::abs(s.h);
            Lanes3 step, next;
            const Mask definite = definite_step(s, Ops::every(0x1p-30) * scale, step, next);
            dropped |= active & ~definite;
            active &= definite;
            const Lanes length2 = Ops::dot(step, step);
            const Mask converged = active & (length2 < Ops::every(kStepTolerance * kStepTolerance));
            result = chosen(converged, s, result);
            done |= converged;
            active &= ~converged;
            dropped |= active & (length2 > Ops::every(kTrustRadius * kTrustRadius));
            active &= ~dropped;
            const Mask quadratic = length2 < Ops::every(kQuadraticRegion * kQuadraticRegion);
            const Mask last =
                active & quadratic &
                ((length2 < Ops::every(kLastStep * kLastStep)) |
                 (length2 * length2 * length2 <=
                  Ops::every(kDirectionTolerance * kDirectionTolerance) * previous2 * previous2));
            if (Ops::bits(last) != 0) result = chosen(last, stepped(s, step), result);
            done |= last;
            active &= ~last;
            if (Ops::bits(active) == 0) break;
            const Sample trial = at(next);
            // Outside the quadratic region the scalar code takes the step only where h does
            // not increase: elsewhere it halves the step, which leaves the path. Its other
            // exit there, a trial whose n has not moved, needs no test here: the step is
            // tangent and at least 2^-20 rad long, so the trial's n differs from s.n (only
            // the halvings make it that short).
            dropped |= active & ~quadratic & ~(trial.h <= s.h);
            active &= ~dropped;
            previous2 = Ops::select(active, length2, previous2);
            s = chosen(active, trial, s);
            evaluations += Ops::select(active, Ops::every(1.0), Ops::every(0.0));
        }
        // solve_pair's certificates and its last normalisation.
        const Lanes h = result.h;
        const Lanes inscribed = ra2_.z * result.inv_a + rb2_.z * result.inv_b;
        const Mask kept =
            done & ((h < Ops::every(0.0)) | (h <= inscribed + Ops::every(kSearchTolerance)));
        const Lanes3 n =
            (Ops::every(1.5) - Ops::every(0.5) * Ops::dot(result.n, result.n)) * result.n;
        const unsigned bits = Ops::bits(kept);
        for (int k = 0; k < N; ++k) {
            if ((bits & (1u << k)) == 0) continue;
            const bool separated = h[k] < 0.0;
            *solutions[k] = {h[k],
                             {n.x[k], n.y[k], n.z[k]},
                             {result.xa.x[k], result.xa.y[k], result.xa.z[k]},
                             -glm::dvec3(result.xb.x[k], result.xb.y[k], result.xb.z[k]),
                             separated ? PairPath::separated : PairPath::inscribed_balls,
                             int(evaluations[k]),
                             h[k]};
        }
        return bits;
    }

  private:
    // PairFunction's Sample, a lane per frame.
    struct Sample {
        Lanes3 n;
        Lanes h;
        Lanes3 p, xa, xb;
        Lanes a, b, inv_a, inv_b;
    };

    [[gnu::always_inline]] static Lanes3 times(const Lanes3& u, const Lanes3& v) {
        return {u.x * v.x, u.y * v.y, u.z * v.z};
    }
    [[gnu::always_inline]] static Lanes component(const Lanes3& u, int i) {
        return i == 0 ? u.x : i == 1 ? u.y : u.z;
    }
    // PairFunction::support_matrix's entry (i, j), in its order. A member, not a lambda: a
    // lambda is not forced inline, and at -O0 it would return a 32-byte vector from code of
    // the library's own level to the AVX2 caller (lane_ops.hpp).
    [[gnu::always_inline]] Lanes support_entry(int i, int j) const {
        return rb2_.x * component(b_axes_[0], i) * component(b_axes_[0], j) +
               rb2_.y * component(b_axes_[1], i) * component(b_axes_[1], j) +
               rb2_.z * component(b_axes_[2], i) * component(b_axes_[2], j);
    }
    [[gnu::always_inline]] static Lanes3 chosen(const Mask& where, const Lanes3& u,
                                                const Lanes3& v) {
        return {Ops::select(where, u.x, v.x), Ops::select(where, u.y, v.y),
                Ops::select(where, u.z, v.z)};
    }
    [[gnu::always_inline]] static Sample chosen(const Mask& where, const Sample& u,
                                                const Sample& v) {
        return {chosen(where, u.n, v.n),
                Ops::select(where, u.h, v.h),
                chosen(where, u.p, v.p),
                chosen(where, u.xa, v.xa),
                chosen(where, u.xb, v.xb),
                Ops::select(where, u.a, v.a),
                Ops::select(where, u.b, v.b),
                Ops::select(where, u.inv_a, v.inv_a),
                Ops::select(where, u.inv_b, v.inv_b)};
    }
    // glm's v * R (R^T v): column j dotted with v.
    [[gnu::always_inline]] Lanes3 in_b(const Lanes3& v) const {
        return {Ops::dot(b_axes_[0], v), Ops::dot(b_axes_[1], v), Ops::dot(b_axes_[2], v)};
    }
    // glm's R * v: the columns times v's components, summed in column order.
    [[gnu::always_inline]] Lanes3 from_b(const Lanes3& v) const {
        return v.x * b_axes_[0] + v.y * b_axes_[1] + v.z * b_axes_[2];
    }
    // PairFunction::mb.
    [[gnu::always_inline]] Lanes3 mb(const Lanes3& v) const {
        return {mb_[0] * v.x + mb_[3] * v.y + mb_[4] * v.z,
                mb_[3] * v.x + mb_[1] * v.y + mb_[5] * v.z,
                mb_[4] * v.x + mb_[5] * v.y + mb_[2] * v.z};
    }

    /// first_guess, where the guess is the system's solution (the lanes it holds for): not
    /// where its squared length is beyond 2^-600..2^600 and the scalar code falls back to d.
    [[gnu::always_inline]] Mask first_guess(Lanes3& guess) const {
        const Lanes3& d = d_;
        const Lanes d2 = Ops::dot(d, d);
        const Lanes big_a = Ops::sqrt(Ops::dot(times(ra2_, d), d));
        const Lanes big_b = Ops::sqrt(Ops::dot(times(rb2_, d_in_b_), d_in_b_));
        const Lanes linear = big_a * big_b * (big_a + big_b - d2);
        const Lanes capped = Ops::every(0.5) * d2 * (ra2_.z * big_b + rb2_.z * big_a);
        const Lanes shift = Ops::select(capped < linear, capped, linear);  // std::min
        const Lanes wa = d2 * big_b, wb = d2 * big_a;
        const Lanes m00 = wa * ra2_.x + wb * mb_[0] - shift,
                    m11 = wa * ra2_.y + wb * mb_[1] - shift,
                    m22 = wa * ra2_.z + wb * mb_[2] - shift;
        const Lanes m01 = wb * mb_[3], m02 = wb * mb_[4], m12 = wb * mb_[5];
        const Lanes c00 = m11 * m22 - m12 * m12, c01 = m02 * m12 - m01 * m22,
                    c02 = m01 * m12 - m02 * m11, c11 = m00 * m22 - m02 * m02,
                    c12 = m01 * m02 - m00 * m12, c22 = m00 * m11 - m01 * m01;
        const Lanes3 solved{c00 * d.x + c01 * d.y + c02 * d.z, c01 * d.x + c11 * d.y + c12 * d.z,
                            c02 * d.x + c12 * d.y + c22 * d.z};
        const Lanes length2 = Ops::dot(solved, solved);
        const Lanes3 negated{-solved.x, -solved.y, -solved.z};
        // Outside 2^-60..2^60, the scalar code's power of two 2^-e for length2 in
        // [2^2e, 2^(2e+2)), from the exponent bits.
        const Mask exponent = ((Ops::to_bits(length2) >> 52) & 0x7ff) - 1023;
        const Lanes scale = Ops::from_bits((1023 - (exponent >> 1)) << 52);
        const Mask in_range = (length2 >= Ops::every(0x1p-60)) & (length2 <= Ops::every(0x1p60));
        guess = chosen(in_range, negated, scale * negated);
        return (length2 > Ops::every(0x1p-600)) & (length2 < Ops::every(0x1p600));
    }

    /// PairFunction::at.
    [[gnu::always_inline]] Sample at(const Lanes3& m) const {
        Sample s;
        const Lanes l2 = Ops::dot(m, m);
        const Lanes3 ma = times(ra2_, m);
        const Lanes a2 = Ops::dot(ma, m);
        const Lanes3 wb = in_b(m);
        const Lanes3 scaled_b = times(rb_, wb);
        const Lanes b2 = Ops::dot(scaled_b, scaled_b);
        const Lanes inverse_square = Ops::every(1.0) / (l2 * a2 * b2);
        const Lanes l = Ops::sqrt(l2), big_a = Ops::sqrt(a2), big_b = Ops::sqrt(b2);
        const Lanes q = l * big_a * big_b * inverse_square;
        const Lanes inv_l = big_a * big_b * q;
        const Lanes l2q = l * l * q;
        s.n = inv_l * m;
        s.a = big_a * inv_l;
        s.b = big_b * inv_l;
        s.inv_a = l2q * big_b;
        s.inv_b = l2q * big_a;
        const Lanes inv_big_a = l * big_b * q, inv_big_b = l * big_a * q;
        s.xa = inv_big_a * ma;
        s.xb = inv_big_b * from_b(times(rb2_, wb));
        s.h = Ops::dot(d_, s.n) + s.a + s.b;
        s.p = d_ + s.xa + s.xb;
        return s;
    }

    /// PairFunction::definite_step: the lanes whose Hessian is definite.
    [[gnu::always_inline]] Mask definite_step(const Sample& s, const Lanes& floor, Lanes3& step,
                                              Lanes3& next) const {
        const Lanes3 fa = s.inv_a * s.xa, fb = s.inv_b * s.xb;
        const Lanes along = s.h + s.a + s.b;
        const Lanes3 fn = along * s.n;
        const Lanes s00 = (ra2_.x * s.inv_a - s.h) + mb_[0] * s.inv_b - fa.x * s.xa.x -
                          fb.x * s.xb.x + fn.x * s.n.x;
        const Lanes s11 = (ra2_.y * s.inv_a - s.h) + mb_[1] * s.inv_b - fa.y * s.xa.y -
                          fb.y * s.xb.y + fn.y * s.n.y;
        const Lanes s22 = (ra2_.z * s.inv_a - s.h) + mb_[2] * s.inv_b - fa.z * s.xa.z -
                          fb.z * s.xb.z + fn.z * s.n.z;
        const Lanes s01 = mb_[3] * s.inv_b - fa.x * s.xa.y - fb.x * s.xb.y + fn.x * s.n.y;
        const Lanes s02 = mb_[4] * s.inv_b - fa.x * s.xa.z - fb.x * s.xb.z + fn.x * s.n.z;
        const Lanes s12 = mb_[5] * s.inv_b - fa.y * s.xa.z - fb.y * s.xb.z + fn.y * s.n.z;
        const Lanes c00 = s11 * s22 - s12 * s12, c01 = s02 * s12 - s01 * s22,
                    c02 = s01 * s12 - s02 * s11, c11 = s00 * s22 - s02 * s02,
                    c12 = s01 * s02 - s00 * s12, c22 = s00 * s11 - s01 * s01;
        const Lanes det = s00 * c00 + s01 * c01 + s02 * c02;
        const Lanes normal_part = s.a + s.b;
        const Lanes sum = s00 + s11 + s22 - normal_part;
        const Mask definite =
            (sum > Ops::every(2.0) * floor) & (det > normal_part * floor * (sum - floor));
        const Lanes3 g = s.p - s.h * s.n;
        const Lanes scale = Ops::every(-1.0) / det;
        const Lanes3 solved{c00 * g.x + c01 * g.y + c02 * g.z, c01 * g.x + c11 * g.y + c12 * g.z,
                            c02 * g.x + c12 * g.y + c22 * g.z};
        step = scale * solved;
        next = chosen((det >= Ops::every(0x1p-29)) & (det <= Ops::every(0x1p29)),
                      det * s.n - solved, s.n + step);
        return definite;
    }

    /// PairFunction::stepped.
    [[gnu::always_inline]] Sample stepped(const Sample& s, const Lanes3& step) const {
        Sample t;
        const Lanes3 m = s.n + step;
        t.n = (Ops::every(1.5) - Ops::every(0.5) * Ops::dot(m, m)) * m;
        const Lanes da = Ops::dot(s.xa, step), db = Ops::dot(s.xb, step);
        t.xa = s.xa + s.inv_a * (times(ra2_, step) - da * s.xa);
        t.xb = s.xb + s.inv_b * (mb(step) - db * s.xb);
        t.a = s.a + da;
        t.b = s.b + db;
        t.inv_a = s.inv_a * (Ops::every(1.0) - da * s.inv_a);
        t.inv_b = s.inv_b * (Ops::every(1.0) - db * s.inv_b);
        t.h = s.h + Ops::every(0.5) * Ops::dot(s.p - s.h * s.n, step);
        t.p = d_ + t.xa + t.xb;
        return t;
    }

    Lanes3 ra2_, rb2_, rb_;
    Lanes3 b_axes_[3];  // B's sorted axes in A's frame, column j in b_axes_[j]
    Lanes3 d_, d_in_b_;
    std::array<Lanes, 6> mb_;
};

}  // namespace trackphys::detail
