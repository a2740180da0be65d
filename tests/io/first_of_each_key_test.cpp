// FirstOfEachKey against a brute-force map from key to first index, over long lists with
// many repeated keys (its table grows many times), with a well-mixed hash and with one
// that makes every key collide in the slot and in the tag.

#include "io/first_of_each_key.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <map>
#include <random>
#include <vector>

#include <gtest/gtest.h>

namespace trackphys::detail {
namespace {

using Corners = std::array<std::uint32_t, 3>;

Corners sorted(Corners c) {
    std::sort(c.begin(), c.end());
    return c;
}

struct SortedCorners {
    Corners operator()(const Corners& c) const { return sorted(c); }
    std::uint64_t hash(const Corners& s) const {
        std::uint64_t h = 1469598103934665603ull;
        for (const std::uint32_t x : s) h = (h ^ x) * 0x100000001b3ull * 0x9E3779B97F4A7C15ull;
        return h ^ (h >> 32);
    }
};

// Every key in one slot with one tag: each probe walks the cluster and compares keys.
struct CollidingCorners {
    Corners operator()(const Corners& c) const { return sorted(c); }
    std::uint64_t hash(const Corners&) const { return 0x1234567800000005ull; }
};

template <class KeyOf>
void expect_first_indices(std::uint32_t pool, int elements, std::uint32_t seed) {
    std::mt19937 random(seed);
    std::uniform_int_distribution<std::uint32_t> corner(0, pool - 1);
    std::vector<Corners> list;
    FirstOfEachKey<Corners, KeyOf> first(list);
    std::map<Corners, std::size_t> first_by_key;
    std::size_t repeats = 0;
    for (int i = 0; i < elements; ++i) {
        // Appended and kept, as the vertex welder does: indices stay those of the list.
        list.push_back({corner(random), corner(random), corner(random)});
        const std::size_t last = list.size() - 1;
        const auto [it, inserted] = first_by_key.try_emplace(sorted(list.back()), last);
        ASSERT_EQ(first.first_of(last), it->second) << "pool " << pool << ", element " << i;
        if (!inserted) ++repeats;
    }
    EXPECT_GT(repeats, 0u) << "pool " << pool;
}

TEST(FirstOfEachKey, GivesTheFirstIndexOfEachKeyAsAMapDoes) {
    for (const std::uint32_t pool : {3u, 12u, 60u, 400u})
        expect_first_indices<SortedCorners>(pool, 100000, 20261129 + pool);
}

TEST(FirstOfEachKey, GivesTheFirstIndexWhenEveryHashCollides) {
    for (const std::uint32_t pool : {3u, 12u, 30u})
        expect_first_indices<CollidingCorners>(pool, 3000, pool);
}

TEST(FirstOfEachKey, AReservedTableAnswersAsAGrowingOne) {
    std::vector<Corners> list;
    FirstOfEachKey<Corners, SortedCorners> first(list);
    first.reserve(5);
    for (const Corners& c : {Corners{4, 7, 9}, Corners{9, 7, 4}, Corners{7, 9, 4}, Corners{4, 7, 8},
                             Corners{4, 4, 7}, Corners{7, 4, 4}})
        list.push_back(c);
    const std::vector<std::size_t> expected{0, 0, 0, 3, 4, 4};
    for (std::size_t i = 0; i < list.size(); ++i) EXPECT_EQ(first.first_of(i), expected[i]) << i;
}

}  // namespace
}  // namespace trackphys::detail
