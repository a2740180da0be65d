#include "geometry/ellipsoid_pair_lanes.hpp"

#include <algorithm>
#include <cstddef>
#include <span>

#include "core/cpu_features.hpp"
#include "geometry/ellipsoid_pair_kernel.hpp"

// solve_pairs_on_common_path: the frames N at a time through PairLanes, in four lanes with
// AVX2 (chosen at run time, as the cull's), else in two.

namespace trackphys::detail {
namespace {

/// The frames N at a time; two or three at the end repeat the last frame in the lanes left
/// over (their answers are dropped). A lone last frame is left to the caller's solve_pair,
/// which takes less time than a block of lanes for one pair.
template <int N>
[[gnu::always_inline]] inline void solve_in_lanes(std::span<const PairFrame> frames,
                                                  std::span<PairSolution> solutions,
                                                  std::span<bool> kept) {
    PairSolution spare;
    for (std::size_t start = 0; start < frames.size(); start += N) {
        const std::size_t count = std::min<std::size_t>(N, frames.size() - start);
        if (count == 1) {
            kept[start] = false;
            break;
        }
        const PairFrame* block[N];
        PairSolution* out[N];
        for (std::size_t k = 0; k < N; ++k) {
            block[k] = &frames[start + std::min(k, count - 1)];
            out[k] = k < count ? &solutions[start + k] : &spare;
        }
        const unsigned bits = PairLanes<N>(block).solve(out);
        for (std::size_t k = 0; k < count; ++k) kept[start + k] = (bits >> k & 1u) != 0;
    }
}

#if defined(__x86_64__) || defined(__i386__)
// No FMA: the lanes must round as the scalar kernel does.
[[gnu::target("avx2")]] void solve_in_four_lanes(std::span<const PairFrame> frames,
                                                 std::span<PairSolution> solutions,
                                                 std::span<bool> kept) {
    solve_in_lanes<4>(frames, solutions, kept);
}
#endif

[[gnu::noinline]] void solve_in_two_lanes(std::span<const PairFrame> frames,
                                          std::span<PairSolution> solutions, std::span<bool> kept) {
    solve_in_lanes<2>(frames, solutions, kept);
}

}  // namespace

void solve_pairs_on_common_path(std::span<const PairFrame> frames,
                                std::span<PairSolution> solutions, std::span<bool> kept) {
#if defined(__x86_64__) || defined(__i386__)
    if (use_four_lanes()) return solve_in_four_lanes(frames, solutions, kept);
#endif
    solve_in_two_lanes(frames, solutions, kept);
}

}  // namespace trackphys::detail
