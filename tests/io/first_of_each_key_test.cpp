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
        // Appended and kept, repeats too (load_mesh pops a repeat instead): indices stay the
        // list's.
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

// reserve sizes the table for what it will hold, not only its default 16 slots: answers
// are the same from a reserved table that later grows past its reservation.
TEST(FirstOfEachKey, AReservedTableAnswersAsAGrowingOne) {
    std::mt19937 random(7);
    std::uniform_int_distribution<std::uint32_t> corner(0, 40);
    std::vector<Corners> list(20000);
    for (Corners& c : list) c = {corner(random), corner(random), corner(random)};
    FirstOfEachKey<Corners, SortedCorners> growing(list), reserved(list);
    reserved.reserve(3000);
    for (std::size_t i = 0; i < list.size(); ++i)
        ASSERT_EQ(reserved.first_of(i), growing.first_of(i)) << i;
}

}  // namespace
}  // namespace trackphys::detail
