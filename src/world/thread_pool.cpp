#include "world/thread_pool.hpp"

#include <chrono>
#include <string>
#include <system_error>

#include "trackphys/error.hpp"

namespace trackphys::detail {

namespace {

// Long enough for the other side to finish an island of a car or two, the usual wait at
// the end of a run; short enough that a worker between a game's updates soon sleeps.
constexpr auto kSpin = std::chrono::microseconds(100);

void relax() {
#if defined(__x86_64__) || defined(__i386__)
    __builtin_ia32_pause();
#endif
}

// Waits while keep_waiting(value) holds and returns the value that ended it: spins for up
// to kSpin, then sleeps on the atomic until it changes.
template <class T, class KeepWaiting>
T await(const std::atomic<T>& value, KeepWaiting keep_waiting) {
    const auto spin_until = std::chrono::steady_clock::now() + kSpin;
    bool spinning = true;
    for (T seen = value.load();; seen = value.load()) {
        if (!keep_waiting(seen)) return seen;
        if (spinning) {
            for (int i = 0; i < 64; ++i) relax();
            spinning = std::chrono::steady_clock::now() < spin_until;
        } else {
            value.wait(seen);
        }
    }
}

}  // namespace

ThreadPool::ThreadPool(int threads) {
    try {
        for (int worker = 1; worker < threads; ++worker)
            threads_.emplace_back([this, worker] { serve(worker); });
    } catch (const std::system_error& e) {
        // The workers already started are joined: destroyed joinable, they would end the
        // program (no destructor runs for a constructor that throws).
        stop_workers();
        throw Error("WorldSettings.threads: could not start worker thread " +
                    std::to_string(threads_.size() + 1) + " of " + std::to_string(threads - 1) +
                    " (" + e.what() + ")");
    }
}

ThreadPool::~ThreadPool() { stop_workers(); }

void ThreadPool::stop_workers() {
    stopping_.store(true);
    task_state_.fetch_add(2);
    task_state_.notify_all();
    for (std::thread& thread : threads_) thread.join();
}

void ThreadPool::run(TaskCallback* task, int item_count, void* context) {
    // No worker is inside a task now (the last run waited for them to leave), so these
    // writes race with nothing; opening the task publishes them.
    task_ = task;
    context_ = context;
    item_count_ = item_count;
    next_item_.store(0, std::memory_order_relaxed);
    finished_items_.store(0, std::memory_order_relaxed);
    const std::uint32_t open = task_state_.load(std::memory_order_relaxed) + 1;
    task_state_.store(open);
    task_state_.notify_all();
    claim_items(0);
    await(finished_items_, [&](int finished) { return finished < item_count; });
    // Closed, the task takes no more workers; the ones inside are awake and about to leave.
    task_state_.store(open + 1);
    await(joined_, [](int joined) { return joined > 0; });
}

void ThreadPool::serve(int worker) {
    std::uint32_t done_with = task_state_.load();
    for (;;) {
        const std::uint32_t state = await(task_state_, [&](std::uint32_t s) {
            return !stopping_.load() && (s == done_with || (s & 1u) == 0);
        });
        if (stopping_.load()) return;
        if (join(state)) {
            claim_items(worker);
            leave();
        }
        done_with = state;
    }
}

// Joining, then checking that the task is still open, pairs with run() closing it, then
// counting who joined (both sequentially consistent): either run() waits for this worker,
// or this worker sees the task closed and does not touch it.
bool ThreadPool::join(std::uint32_t task_state) {
    joined_.fetch_add(1);
    if (task_state_.load() == task_state) return true;
    leave();
    return false;
}

void ThreadPool::leave() {
    if (joined_.fetch_sub(1) == 1) joined_.notify_one();
}

void ThreadPool::claim_items(int worker) noexcept {
    for (int item = next_item_.fetch_add(1, std::memory_order_relaxed); item < item_count_;
         item = next_item_.fetch_add(1, std::memory_order_relaxed)) {
        task_(item, item + 1, worker, context_);
        if (finished_items_.fetch_add(1) + 1 == item_count_) finished_items_.notify_one();
    }
}

}  // namespace trackphys::detail
