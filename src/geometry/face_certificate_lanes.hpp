#pragma once

#include <algorithm>
#include <cstddef>
#include <span>

#include "core/cpu_features.hpp"
#include "geometry/lane_ops.hpp"
#include "trackphys/geometry/ellipsoid.hpp"
#include "trackphys/geometry/face_certificate.hpp"
#include "trackphys/geometry/normalized_triangle.hpp"

namespace trackphys::detail {

/// certified_face_contact(*t[k], *e[k]) for k < count, bit for bit: certified[k] whether it
/// holds, and then out[k] its answer (else out[k] is left as it was). Lane k runs the scalar
/// function's IEEE operations in its order (glm's dot, vector-matrix and matrix-vector
/// products and length written out in theirs), and its choices (the push direction, fabs,
/// the proof's tests) by bits and masks, which is what the scalar ?: and fabs give. Lanes
/// from count on hold a repeated pair and are not stored.
template <int N>
[[gnu::always_inline]] inline void certify_block(const NormalizedTriangle* const (&t)[N],
                                                 const Ellipsoid* const (&e)[N],
                                                 ContactWithSupport* out, bool* certified,
                                                 std::size_t count) {
    using Ops = LaneOps<N>;
    using Lanes = typename Ops::Lanes;
    using Mask = typename Ops::Mask;
    using Lanes3 = typename Ops::Lanes3;
    const typename Ops::Frames f = Ops::frames(t);
    const glm::dvec3 *centers[N], *radii[N], *axis0[N], *axis1[N], *axis2[N];
    for (int k = 0; k < N; ++k) {
        centers[k] = &e[k]->center();
        radii[k] = &e[k]->sorted_radii();
        axis0[k] = &e[k]->sorted_axes()[0];
        axis1[k] = &e[k]->sorted_axes()[1];
        axis2[k] = &e[k]->sorted_axes()[2];
    }
    const Lanes3 c = Ops::gather(centers);
    const Lanes3 r = Ops::gather(radii);
    const Lanes3 a0 = Ops::gather(axis0), a1 = Ops::gather(axis1), a2 = Ops::gather(axis2);

    const Lanes3 local{c.x - f.origin.x, c.y - f.origin.y, c.z - f.origin.z};
    const Lanes z = Ops::dot(f.normal, local);
    const Lanes x = Ops::dot(f.dir_x, local);
    const Lanes y = Ops::dot(f.dir_y, local);
    const Mask up = z >= 0.0;
    const Lanes3 u{Ops::select(up, f.normal.x, -f.normal.x),
                   Ops::select(up, f.normal.y, -f.normal.y),
                   Ops::select(up, f.normal.z, -f.normal.z)};
    const Lanes3 stretched{r.x * Ops::dot(a0, u), r.y * Ops::dot(a1, u), r.z * Ops::dot(a2, u)};
    const Lanes h = Ops::sqrt(Ops::dot(stretched, stretched));
    const Lanes g = h - Ops::abs(z);
    const Lanes3 d{r.x * stretched.x, r.y * stretched.y, r.z * stretched.z};
    const Lanes towards = -1.0 / h;
    const Lanes3 extreme{(a0.x * d.x + a1.x * d.y + a2.x * d.z) * towards,
                         (a0.y * d.x + a1.y * d.y + a2.y * d.z) * towards,
                         (a0.z * d.x + a1.z * d.y + a2.z * d.z) * towards};
    const Lanes px = x + Ops::dot(f.dir_x, extreme);
    const Lanes py = y + Ops::dot(f.dir_y, extreme);

    const Lanes scale = Ops::abs(x) + Ops::abs(y) + Ops::abs(z) + f.x1 + r.x;
    const Lanes margin = 0x1p-36 * scale;
    const Mask thick = (f.y2 >= 0x1p-10 * f.x1) & (scale * f.x1 <= 2e5 * f.y2);
    const Mask off_first = py >= margin;
    const Mask off_second =
        (f.x2 - f.x1) * py - f.y2 * (px - f.x1) >= margin * (f.x1 - f.x2 + f.y2);
    const Mask off_third = f.y2 * px - f.x2 * py >= margin * (f.x2 + f.y2);
    const Mask closest = (g + margin) * h * (1.0 + 0x1p-36) < r.z * r.z;
    const Mask holds = thick & off_first & off_second & off_third & closest;
    const Lanes half_g = 0.5 * g;
    const Lanes3 point{c.x + extreme.x + half_g * u.x, c.y + extreme.y + half_g * u.y,
                       c.z + extreme.z + half_g * u.z};
    for (std::size_t k = 0; k < count; ++k) {
        certified[k] = holds[k] != 0;
        if (certified[k])
            out[k] = {{g[k], {u.x[k], u.y[k], u.z[k]}, {point.x[k], point.y[k], point.z[k]}}, h[k]};
    }
}

/// certify_block over every pair (frames[j], ellipsoids[j]), N at a time, into out[j] and
/// certified[j]; a short last block repeats its last pair in the lanes left over. Plain
/// arrays, not optionals, so that a caller's scratch on its stack needs no clearing.
template <int N>
[[gnu::always_inline]] inline void certify_faces(std::span<const NormalizedTriangle* const> frames,
                                                 std::span<const Ellipsoid* const> ellipsoids,
                                                 ContactWithSupport* out, bool* certified) {
    for (std::size_t j = 0; j < frames.size(); j += N) {
        const std::size_t count = std::min<std::size_t>(N, frames.size() - j);
        const NormalizedTriangle* t[N];
        const Ellipsoid* e[N];
        for (std::size_t k = 0; k < N; ++k) {
            t[k] = frames[j + std::min(k, count - 1)];
            e[k] = ellipsoids[j + std::min(k, count - 1)];
        }
        certify_block<N>(t, e, out + j, certified + j, count);
    }
}

#if defined(__x86_64__) || defined(__i386__)
/// certify_faces in four lanes, compiled for AVX2 whatever the library's x86-64 level (no
/// FMA: the lanes must round as the scalar certificate does). Call it only where
/// cpu_has_avx2().
[[gnu::target("avx2")]] inline void certify_faces_avx2(
    std::span<const NormalizedTriangle* const> frames, std::span<const Ellipsoid* const> ellipsoids,
    ContactWithSupport* out, bool* certified) {
    certify_faces<4>(frames, ellipsoids, out, certified);
}
#endif

/// certify_faces in two lanes, out of line like the four-lane one.
[[gnu::noinline]] inline void certify_faces_two_lanes(
    std::span<const NormalizedTriangle* const> frames, std::span<const Ellipsoid* const> ellipsoids,
    ContactWithSupport* out, bool* certified) {
    certify_faces<2>(frames, ellipsoids, out, certified);
}

/// certify_faces in the widest lanes this CPU runs: four with AVX2, else two (SSE2).
inline void certify_faces_widest([[maybe_unused]] bool avx2,
                                 std::span<const NormalizedTriangle* const> frames,
                                 std::span<const Ellipsoid* const> ellipsoids,
                                 ContactWithSupport* out, bool* certified) {
#if defined(__x86_64__) || defined(__i386__)
    if (avx2) return certify_faces_avx2(frames, ellipsoids, out, certified);
#endif
    certify_faces_two_lanes(frames, ellipsoids, out, certified);
}

}  // namespace trackphys::detail
