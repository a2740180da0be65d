// Packing a block's kept lanes to the front (src/collision/lane_compaction.hpp): both
// tables, and the byte shuffle of the x86-64-v2 build, against a plain statement of it for
// every mask.

#include "collision/lane_compaction.hpp"

#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

#include "trackphys/build_target.hpp"

namespace trackphys {
namespace {

using collision_detail::kCompactedLanes;

// The set lanes of `mask` (of `lanes`), in increasing order.
std::vector<unsigned> set_lanes(unsigned mask, unsigned lanes) {
    std::vector<unsigned> out;
    for (unsigned i = 0; i < lanes; ++i)
        if ((mask >> i) & 1u) out.push_back(i);
    return out;
}

TEST(LaneCompaction, EightLaneTableListsTheSetLanesThenLaneZero) {
    for (unsigned mask = 0; mask < 256; ++mask) {
        const std::vector<unsigned> expected = set_lanes(mask, 8);
        const auto& c = kCompactedLanes[mask];
        ASSERT_EQ(c.count, expected.size()) << "mask " << mask;
        for (unsigned k = 0; k < 8; ++k)
            ASSERT_EQ(c.lane[k], k < expected.size() ? expected[k] : 0u) << "mask " << mask;
    }
}

TEST(LaneCompaction, FourLaneShufflesMoveWholeLanesToTheFront) {
    for (unsigned mask = 0; mask < 16; ++mask) {
        const std::vector<unsigned> expected = set_lanes(mask, 4);
        const auto& shuffle = collision_detail::kFourLaneShuffles[mask].byte;
        for (unsigned b = 0; b < 16; ++b) {
            const unsigned to_lane = b / 4;
            const unsigned want =
                to_lane < expected.size() ? 4 * expected[to_lane] + b % 4 : 0x80u;  // 0x80: zero
            ASSERT_EQ(shuffle[b], want) << "mask " << mask << " byte " << b;
        }
    }
}

#if defined(__SSSE3__)
TEST(LaneCompaction, PackFourLanesKeepsTheSetLanesInOrderAndZeroesTheRest) {
    alignas(16) const std::uint32_t lanes[4] = {0xdeadbeefu, 7u, 0x80000000u, 123456789u};
    for (unsigned mask = 0; mask < 16; ++mask) {
        alignas(16) std::uint32_t packed[4];
        _mm_store_si128(reinterpret_cast<__m128i*>(packed),
                        collision_detail::pack_four_lanes(
                            _mm_load_si128(reinterpret_cast<const __m128i*>(lanes)), mask));
        const std::vector<unsigned> expected = set_lanes(mask, 4);
        for (unsigned k = 0; k < 4; ++k)
            ASSERT_EQ(packed[k], k < expected.size() ? lanes[expected[k]] : 0u) << "mask " << mask;
    }
}
#endif

// The build's own target runs here (CI builds the default, x86-64-v2, and runs it), and
// the name matches what the compiler was told.
TEST(BuildTarget, ThisCpuRunsTheBuildTarget) {
    EXPECT_TRUE(cpu_runs_build_target());
#if defined(__x86_64__) && defined(__SSE4_2__)
    EXPECT_STREQ(build_target(), "x86-64-v2");
#elif defined(__x86_64__)
    EXPECT_STREQ(build_target(), "x86-64");
#endif
}

}  // namespace
}  // namespace trackphys
