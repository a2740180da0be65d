#pragma once

// Runs independent jobs (one collider's BVH or plane tree each) on a few short-lived
// threads, for builds done once: World's start, bake_map, load_map.

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <thread>
#include <vector>

namespace trackphys::detail {

/// `threads` resolved: 0 is one per core.
inline unsigned resolved_thread_count(unsigned threads) {
    return threads == 0 ? std::max(1u, std::thread::hardware_concurrency()) : threads;
}

/// The threads each of `count` items may run on inside it when run_items_in_parallel runs
/// them on `threads`: those a thread of its own leaves over when there are fewer items than
/// threads (one big collider gets them all), so that all together stay within `threads`.
inline unsigned threads_per_item(std::size_t count, unsigned threads) {
    threads = resolved_thread_count(threads);
    return count < threads ? static_cast<unsigned>(threads / std::max<std::size_t>(count, 1)) : 1;
}

/// Calls work(i) for every i in [0, count) on up to `threads` threads (0: one per core), the
/// caller's included, and returns when all are done. Threads claim the next item in turn,
/// so each item runs once whatever the thread count; results written to item i's place make
/// the outcome independent of it. Once an item throws, no item above it is begun (a refused
/// mesh or a cancelled bake ends the build at once rather than after every item); every item
/// below it still runs, so the exception rethrown, the lowest item's, is the one a serial
/// loop reports first.
template <class Work>
void run_items_in_parallel(std::size_t count, unsigned threads, Work&& work) {
    std::vector<std::exception_ptr> errors(count);
    std::atomic<std::size_t> next{0};
    std::atomic<std::size_t> lowest_thrower{count};
    auto claim = [&] {
        for (std::size_t i = next++; i < count && i < lowest_thrower; i = next++) {
            try {
                work(i);
            } catch (...) {
                errors[i] = std::current_exception();
                std::size_t lowest = lowest_thrower;
                while (i < lowest && !lowest_thrower.compare_exchange_weak(lowest, i)) {}
            }
        }
    };
    threads = resolved_thread_count(threads);
    {
        std::vector<std::jthread> helpers;
        for (std::size_t t = 1; t < std::min<std::size_t>(threads, count); ++t)
            helpers.emplace_back(claim);
        claim();
    }  // joins
    if (lowest_thrower < count) std::rethrow_exception(errors[lowest_thrower]);
}

}  // namespace trackphys::detail
