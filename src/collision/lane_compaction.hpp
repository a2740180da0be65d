#pragma once

// The set lanes of an eight-lane mask, packed to the front, from a table (private). A block
// of eight leaf slots reports its kept lanes without branching on the mask and without a
// per-lane "keep" step: it copies eight slots in the table's order and advances by the
// count. Per lane that is a table byte, a load and a store (the bit-by-bit alternative costs
// about 7.5 instructions a lane, and a loop over set bits mispredicts on mixed masks).

#include <array>
#include <cstdint>

namespace trackphys::collision_detail {

/// For one mask: its set lanes in increasing order, then lane 0 repeated (a lane that is
/// always safe to read), and how many are set. 9 bytes.
struct CompactedLanes {
    std::uint8_t lane[8];
    std::uint8_t count;
};
static_assert(sizeof(CompactedLanes) == 9);

/// All 256 masks (2,304 bytes: a few lines of which a query touches).
inline constexpr std::array<CompactedLanes, 256> kCompactedLanes = [] {
    std::array<CompactedLanes, 256> table{};
    for (unsigned mask = 0; mask < 256; ++mask) {
        CompactedLanes& c = table[mask];
        for (std::uint8_t i = 0; i < 8; ++i)
            if ((mask >> i) & 1u) c.lane[c.count++] = i;
    }
    return table;
}();

}  // namespace trackphys::collision_detail
