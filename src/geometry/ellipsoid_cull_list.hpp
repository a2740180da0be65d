#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <span>

#include "core/cpu_features.hpp"
#include "geometry/ellipsoid_cull_lanes.hpp"

namespace trackphys::detail {

/// The cull's depth bounds of its ellipsoid on the first `count` (1 to N) of `listed`, bit for
/// bit ellipsoid_depth_bound: keep(candidate, bound) for each whose bound is above zero, in
/// list order. Fewer than N repeat the last triangle in the lanes left over.
template <int N, class Candidate, class Keep>
[[gnu::always_inline]] inline void cull_block(const EllipsoidCull<N>& cull, const Candidate* listed,
                                              std::size_t count, Keep& keep) {
    const NormalizedTriangle* triangles[N];
    for (std::size_t j = 0; j < N; ++j) triangles[j] = listed[std::min(j, count - 1)].triangle;
    const std::array<double, N> bounds = cull.depth_bounds(triangles);
    for (std::size_t j = 0; j < count; ++j)
        if (bounds[j] > 0.0) keep(listed[j], bounds[j]);
}

/// cull_block over one ellipsoid's list, N at a time, then its tail in N lanes too: with the
/// frames read in rows, a block of four costs no more instructions than one of two. Whole
/// blocks and the tail are separate calls, so that a whole block's count is known.
template <int N, class Candidate, class Keep>
[[gnu::always_inline]] inline void cull_listed(const Ellipsoid& e,
                                               std::span<const Candidate> listed, Keep& keep) {
    if (listed.empty()) return;
    const EllipsoidCull<N> cull(e);
    const std::size_t tail = listed.size() % N;
    const std::size_t whole = listed.size() - tail;
    for (std::size_t k = 0; k < whole; k += N) cull_block(cull, &listed[k], N, keep);
    if (tail != 0) cull_block(cull, &listed[whole], tail, keep);
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
