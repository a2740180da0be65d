// World's own thread pool: every item of every run exactly once, each worker index on one
// thread at a time, and every item's writes seen by the caller when run returns, over runs
// that follow at once (a worker still spinning) and runs after a pause (a worker asleep).
#include "world/thread_pool.hpp"

#include <atomic>
#include <chrono>
#include <cstdlib>
#include <stdexcept>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

namespace trackphys {
namespace {

struct Tally {
    std::vector<int> runs_of_item;         // plain ints: run() must publish them to the caller
    std::vector<std::atomic<int>> inside;  // per worker index, items running now
    std::atomic<int> worker_overlaps{0};
    std::atomic<int> bad_workers{0};
    int workers = 0;

    Tally(int items, int worker_count)
        : runs_of_item(static_cast<std::size_t>(items)),
          inside(static_cast<std::size_t>(worker_count)),
          workers(worker_count) {}

    static void task(int begin, int end, int worker, void* context) {
        Tally& self = *static_cast<Tally*>(context);
        if (worker < 0 || worker >= self.workers) {
            ++self.bad_workers;
            return;
        }
        std::atomic<int>& inside = self.inside[static_cast<std::size_t>(worker)];
        if (inside.fetch_add(1) != 0) ++self.worker_overlaps;
        // The other threads' items take longer than the caller's: run must wait for them.
        const auto busy = std::chrono::microseconds(worker == 0 ? 20 : 500);
        const auto until = std::chrono::steady_clock::now() + busy;
        while (std::chrono::steady_clock::now() < until) {}
        for (int item = begin; item < end; ++item)
            ++self.runs_of_item[static_cast<std::size_t>(item)];
        inside.fetch_sub(1);
    }
};

TEST(WorldThreads, PoolRunsEveryItemOnceAndPublishesItsWrites) {
    for (const int threads : {2, 4}) {
        detail::ThreadPool pool(threads);
        ASSERT_EQ(pool.thread_count(), threads);
        for (int run = 0; run < 300; ++run) {
            const int items = 1 + run % 7;
            Tally tally(items, threads);
            pool.run(&Tally::task, items, &tally);
            for (int item = 0; item < items; ++item)
                ASSERT_EQ(tally.runs_of_item[static_cast<std::size_t>(item)], 1)
                    << threads << " threads, run " << run << ", item " << item;
            ASSERT_EQ(tally.worker_overlaps.load(), 0);
            ASSERT_EQ(tally.bad_workers.load(), 0);
            // Every tenth run comes after the workers have gone to sleep.
            if (run % 10 == 9) std::this_thread::sleep_for(std::chrono::milliseconds(2));
        }
    }
}

// The pool's worker dawdles in each item it claims, so the caller always claims one of the
// four and throws there.
void throw_from_the_caller(int, int, int worker, void*) {
    if (worker == 0) throw std::runtime_error("an item failed");
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
}

// A task that throws cannot leave the pool half-way through a run (its next run would wait
// on the unfinished one), so the exception ends the program wherever it is thrown, and it
// does not reach run()'s caller as if the pool were still usable.
TEST(WorldThreadsDeathTest, ATaskThatThrowsOnTheCallerEndsTheProgram) {
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    EXPECT_DEATH(
        {
            detail::ThreadPool pool(2);
            try {
                pool.run(&throw_from_the_caller, 4, nullptr);
            } catch (...) {
                std::_Exit(0);
            }
        },
        "");
}

}  // namespace
}  // namespace trackphys
