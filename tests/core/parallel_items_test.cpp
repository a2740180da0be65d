// run_items_in_parallel (src/core/parallel_items.hpp): every item runs once on any thread
// count, and a throwing item is reported as a serial loop would report it.

#include "core/parallel_items.hpp"

#include <atomic>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace trackphys {
namespace {

TEST(ParallelItems, EveryItemRunsOnceOnAnyThreadCount) {
    for (const unsigned threads : {0u, 1u, 2u, 7u}) {
        std::vector<std::atomic<int>> runs(100);
        detail::run_items_in_parallel(runs.size(), threads, [&](std::size_t i) { ++runs[i]; });
        for (std::size_t i = 0; i < runs.size(); ++i) EXPECT_EQ(runs[i], 1) << i;
    }
    detail::run_items_in_parallel(0, 2, [](std::size_t) { FAIL() << "no items, no calls"; });
}

TEST(ParallelItems, TheLowestThrowingItemIsRethrownAfterAllRan) {
    for (const unsigned threads : {1u, 3u}) {
        std::atomic<int> ran{0};
        try {
            detail::run_items_in_parallel(50, threads, [&](std::size_t i) {
                ++ran;
                if (i == 17 || i == 40) throw std::runtime_error("item " + std::to_string(i));
            });
            FAIL() << "no exception";
        } catch (const std::runtime_error& e) {
            EXPECT_EQ(std::string(e.what()), "item 17");
        }
        EXPECT_EQ(ran, 50);
    }
}

}  // namespace
}  // namespace trackphys
