#pragma once

// The set lanes of a mask, packed to the front (private): how a block of eight leaf slots
// reports its kept slots without branching on the mask and without a per-lane "keep" step.
// Two ways, by the instruction set the library is built for (TRACKPHYS_X86_64_LEVEL):
// - x86-64-v2 (SSSE3; the default): each half of four 32-bit lanes is packed by one byte
//   shuffle from a 16-entry table: a load, a shuffle, a store and a popcount per half.
// - x86-64 baseline (SSE2 has no variable shuffle): eight lanes are copied in a table's
//   order, set lanes first; per lane a table byte, a load and a store (the bit-by-bit
//   alternative costs about 7.5 instructions a lane, and a loop over set bits mispredicts
//   on mixed masks). On the default track's car boxes the shuffle speeds up the whole
//   query, not only the packing.
// Both tables are always built and the tests check both against a plain statement; a v1
// build runs the first in scripts/determinism.sh, which must end a drive as v2 does.

#include <emmintrin.h>
#if defined(__SSSE3__)
#include <tmmintrin.h>
#endif

#include <array>
#include <cstdint>

namespace trackphys::collision_detail {

/// For one eight-lane mask: its set lanes in increasing order, then lane 0 repeated (a lane
/// that is always safe to read), and how many are set. 9 bytes.
struct CompactedLanes {
    std::uint8_t lane[8];
    std::uint8_t count;
};
static_assert(sizeof(CompactedLanes) == 9);

/// All 256 eight-lane masks (2,304 bytes: a few lines of which a query touches).
inline constexpr std::array<CompactedLanes, 256> kCompactedLanes = [] {
    std::array<CompactedLanes, 256> table{};
    for (unsigned mask = 0; mask < 256; ++mask) {
        CompactedLanes& c = table[mask];
        for (std::uint8_t i = 0; i < 8; ++i)
            if ((mask >> i) & 1u) c.lane[c.count++] = i;
    }
    return table;
}();

/// For one four-lane mask: the byte shuffle (_mm_shuffle_epi8's control) that moves its set
/// 32-bit lanes to the front, in order, and zeroes the rest. 16 bytes.
struct alignas(16) FourLaneShuffle {
    std::uint8_t byte[16];
};

/// All 16 four-lane masks (256 bytes).
inline constexpr std::array<FourLaneShuffle, 16> kFourLaneShuffles = [] {
    std::array<FourLaneShuffle, 16> table{};
    for (unsigned mask = 0; mask < 16; ++mask) {
        unsigned to = 0;
        for (unsigned lane = 0; lane < 4; ++lane)
            if ((mask >> lane) & 1u) {
                for (unsigned b = 0; b < 4; ++b)
                    table[mask].byte[4 * to + b] = static_cast<std::uint8_t>(4 * lane + b);
                ++to;
            }
        for (unsigned b = 4 * to; b < 16; ++b) table[mask].byte[b] = 0x80;  // zero
    }
    return table;
}();

#if defined(__SSSE3__)
/// The 32-bit lanes of `four` set in `mask` (< 16), packed to the front; zeros after them.
inline __m128i pack_four_lanes(__m128i four, unsigned mask) {
    return _mm_shuffle_epi8(
        four, _mm_load_si128(reinterpret_cast<const __m128i*>(kFourLaneShuffles[mask].byte)));
}
#endif

}  // namespace trackphys::collision_detail
