// The broad phase between cars against brute force on random fields of boxes.
#include "world/car_islands.hpp"

#include <algorithm>
#include <cstdint>
#include <random>
#include <vector>

#include <gtest/gtest.h>

namespace trackphys::detail {
namespace {

std::vector<Aabb> random_boxes(std::mt19937& random, int count, double field) {
    std::uniform_real_distribution<double> where(0.0, field);
    std::uniform_real_distribution<double> size(0.5, 6.0);
    std::vector<Aabb> boxes;
    for (int i = 0; i < count; ++i) {
        const glm::dvec3 min(where(random), where(random) * 0.05, where(random));
        boxes.push_back({min, min + glm::dvec3(size(random), 1.5, size(random))});
    }
    return boxes;
}

// The components of the overlap graph, each car labelled by the smallest car of its own.
std::vector<std::uint32_t> brute_force_islands(const std::vector<Aabb>& boxes) {
    std::vector<std::uint32_t> label(boxes.size());
    for (std::uint32_t i = 0; i < boxes.size(); ++i) label[i] = i;
    for (bool changed = true; changed;) {
        changed = false;
        for (std::uint32_t i = 0; i < boxes.size(); ++i)
            for (std::uint32_t j = 0; j < boxes.size(); ++j)
                if (boxes[i].overlaps(boxes[j]) && label[j] < label[i]) {
                    label[i] = label[j];
                    changed = true;
                }
    }
    return label;
}

TEST(CarIslands, MatchBruteForceOnRandomFields) {
    std::mt19937 random(16);
    CarIslands islands;  // reused, as World reuses it
    for (int trial = 0; trial < 200; ++trial) {
        const int count = 1 + trial % 70;
        const std::vector<Aabb> boxes = random_boxes(random, count, 10.0 + trial);
        islands.build(boxes);

        std::vector<std::pair<std::uint32_t, std::uint32_t>> expected_pairs;
        for (std::uint32_t i = 0; i < boxes.size(); ++i)
            for (std::uint32_t j = i + 1; j < boxes.size(); ++j)
                if (boxes[i].overlaps(boxes[j])) expected_pairs.emplace_back(i, j);
        const std::vector<std::uint32_t> label = brute_force_islands(boxes);

        std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
        std::vector<std::uint32_t> seen(boxes.size(), 0);
        std::uint32_t previous_first = 0;
        for (std::size_t i = 0; i < islands.island_count(); ++i) {
            const auto cars = islands.cars(i);
            ASSERT_FALSE(cars.empty());
            EXPECT_TRUE(std::is_sorted(cars.begin(), cars.end()));
            if (i > 0) {
                EXPECT_GT(cars.front(), previous_first) << "islands by smallest car";
            }
            previous_first = cars.front();
            for (const std::uint32_t car : cars) {
                ++seen[car];
                EXPECT_EQ(label[car], cars.front()) << "car " << car << " in trial " << trial;
            }
            for (const CarPair& pair : islands.pairs(i)) {
                EXPECT_LT(pair.a, pair.b);
                EXPECT_EQ(label[pair.a], cars.front());
                pairs.emplace_back(pair.a, pair.b);
            }
            const auto island_pairs = islands.pairs(i);
            EXPECT_TRUE(std::is_sorted(island_pairs.begin(), island_pairs.end(),
                                       [](const CarPair& p, const CarPair& q) {
                                           return p.a != q.a ? p.a < q.a : p.b < q.b;
                                       }));
        }
        EXPECT_TRUE(std::all_of(seen.begin(), seen.end(), [](std::uint32_t n) { return n == 1; }));
        std::sort(pairs.begin(), pairs.end());
        EXPECT_EQ(pairs, expected_pairs) << "trial " << trial;
        EXPECT_EQ(islands.pair_count(), expected_pairs.size());
    }
}

TEST(CarIslands, NoCarsNoIslands) {
    CarIslands islands;
    islands.build({});
    EXPECT_EQ(islands.island_count(), 0u);
    EXPECT_EQ(islands.pair_count(), 0u);
}

}  // namespace
}  // namespace trackphys::detail
