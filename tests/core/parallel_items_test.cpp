// run_items_in_parallel (src/core/parallel_items.hpp): every item runs once on any thread
// count, a throwing item is reported as a serial loop would report it, and no item above
// it is begun.

#include "core/parallel_items.hpp"

#include <atomic>
#include <chrono>
#include <numeric>
#include <stdexcept>
#include <string>
#include <thread>
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

TEST(ParallelItems, ItemsFewerThanThreadsShareTheRest) {
    EXPECT_EQ(detail::threads_per_item(1, 8), 8u);
    EXPECT_EQ(detail::threads_per_item(3, 8), 2u);
    EXPECT_EQ(detail::threads_per_item(8, 8), 1u);
    EXPECT_EQ(detail::threads_per_item(50, 8), 1u);
    EXPECT_EQ(detail::threads_per_item(0, 4), 4u);
    EXPECT_EQ(detail::threads_per_item(1, 0), detail::resolved_thread_count(0));
    EXPECT_GE(detail::resolved_thread_count(0), 1u);
    EXPECT_EQ(detail::resolved_thread_count(5), 5u);
}

TEST(ParallelItems, NoItemAboveAThrowerBeginsOnOneThread) {
    std::vector<int> ran;
    try {
        detail::run_items_in_parallel(50, 1, [&](std::size_t i) {
            ran.push_back(static_cast<int>(i));
            if (i == 17 || i == 40) throw std::runtime_error("item " + std::to_string(i));
        });
        FAIL() << "no exception";
    } catch (const std::runtime_error& e) {
        EXPECT_EQ(std::string(e.what()), "item 17");
    }
    std::vector<int> up_to_17(18);
    std::iota(up_to_17.begin(), up_to_17.end(), 0);
    EXPECT_EQ(ran, up_to_17);
}

TEST(ParallelItems, TheLowestThrowingItemIsRethrownWhicheverThrowsFirst) {
    // Item 17 throws late, after item 40 (claimed later by another thread) has thrown: every
    // item below 40 still runs, so 17's exception is the one reported, as in a serial loop.
    for (const unsigned threads : {2u, 3u, 7u}) {
        std::vector<std::atomic<int>> runs(200);
        std::atomic<bool> item_40_threw{false};
        try {
            detail::run_items_in_parallel(runs.size(), threads, [&](std::size_t i) {
                ++runs[i];
                if (i == 17) {
                    while (!item_40_threw) std::this_thread::yield();
                    throw std::runtime_error("item 17");
                }
                if (i == 40) {
                    item_40_threw = true;
                    throw std::runtime_error("item 40");
                }
            });
            FAIL() << "no exception";
        } catch (const std::runtime_error& e) {
            EXPECT_EQ(std::string(e.what()), "item 17") << threads << " threads";
        }
        for (std::size_t i = 0; i <= 40; ++i) EXPECT_EQ(runs[i], 1) << i;
    }
}

TEST(ParallelItems, AThrowingFirstItemEndsTheRunOnAnyThreadCount) {
    // The other items take 5 ms each: run to the end, 400 would take 0.5-1 s; the other
    // threads should stop at the item they hold when item 0 throws (half of them would need
    // item 0's thread held off for a third of a second between its claim and its throw).
    for (const unsigned threads : {2u, 4u}) {
        std::atomic<int> ran{0};
        EXPECT_THROW(detail::run_items_in_parallel(400, threads,
                                                   [&](std::size_t i) {
                                                       ++ran;
                                                       if (i == 0) throw std::runtime_error("0");
                                                       std::this_thread::sleep_for(
                                                           std::chrono::milliseconds(5));
                                                   }),
                     std::runtime_error);
        EXPECT_LT(ran, 200) << threads << " threads";
    }
}

}  // namespace
}  // namespace trackphys
