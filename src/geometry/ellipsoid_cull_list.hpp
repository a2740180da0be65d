#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <span>

#include "core/cpu_features.hpp"
#include "geometry/ellipsoid_cull_lanes.hpp"

namespace trackphys::detail {

/// The cull's depth bounds of its ellipsoid on listed triangles N at a time, bit for bit
/// ellipsoid_depth_bound: keep(candidate, bound) for each whose bound is above zero, in list
/// order. A last block of fewer than N repeats its last triangle in the lanes left over.
template <int N, class Candidate, class Keep>
[[gnu::always_inline]] inline void cull_in_lanes(const EllipsoidCull<N>& cull,
                                                 std::span<const Candidate> listed, Keep& keep) {
    for (std::size_t k = 0; k < listed.size(); k += N) {
        const std::size_t count = std::min<std::size_t>(N, listed.size() - k);
        const NormalizedTriangle* triangles[N];
        for (std::size_t j = 0; j < N; ++j)
            triangles[j] = listed[k + std::min(j, count - 1)].triangle;
        const std::array<double, N> bounds = cull.depth_bounds(triangles);
        for (std::size_t j = 0; j < count; ++j)
            if (bounds[j] > 0.0) keep(listed[k + j], bounds[j]);
    }
}

/// cull_in_lanes of one ellipsoid's list, but a tail that fits in half the lanes goes there:
/// a wheel's 4 + 1 or a body's one or two triangles cost less than in four lanes.
template <int N, class Candidate, class Keep>
[[gnu::always_inline]] inline void cull_listed(const Ellipsoid& e,
                                               std::span<const Candidate> listed, Keep& keep) {
    if (listed.empty()) return;
    const EllipsoidCull<N> cull(e);
    if constexpr (N > 2) {
        const std::size_t tail = listed.size() % N;
        if (tail != 0 && tail <= N / 2) {
            cull_in_lanes(cull, listed.first(listed.size() - tail), keep);
            cull_in_lanes(EllipsoidCull<N / 2>(cull), listed.last(tail), keep);
            return;
        }
    }
    cull_in_lanes(cull, listed, keep);
}

#if defined(__x86_64__) || defined(__i386__)
/// cull_listed in four lanes, compiled for AVX2 whatever the library's x86-64 level (no FMA:
/// the lanes must round as the scalar bound does). Call it only where cpu_has_avx2().
template <class Candidate, class Keep>
[[gnu::target("avx2")]] void cull_listed_avx2(const Ellipsoid& e, std::span<const Candidate> listed,
                                              Keep& keep) {
    cull_listed<4>(e, listed, keep);
}
#endif

/// cull_listed in two lanes, out of line like the four-lane one: inlined where the cull's
/// width is chosen, it lengthened the caller's own loop by a path no AVX2 CPU takes.
template <class Candidate, class Keep>
[[gnu::noinline]] void cull_listed_two_lanes(const Ellipsoid& e, std::span<const Candidate> listed,
                                             Keep& keep) {
    cull_listed<2>(e, listed, keep);
}

/// cull_listed in the widest lanes this CPU runs: four with AVX2, else two (SSE2).
template <class Candidate, class Keep>
void cull_listed_widest([[maybe_unused]] bool avx2, const Ellipsoid& e,
                        std::span<const Candidate> listed, Keep& keep) {
#if defined(__x86_64__) || defined(__i386__)
    if (avx2) return cull_listed_avx2(e, listed, keep);
#endif
    cull_listed_two_lanes(e, listed, keep);
}

}  // namespace trackphys::detail
