#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <thread>
#include <vector>

#include "trackphys/world/job_system.hpp"

namespace trackphys::detail {

/// World's own workers when no job system is plugged in: threads - 1 threads that sleep
/// between tasks, and the calling thread, which works too. Items are claimed one at a time
/// from a shared counter, so a large island does not hold up the small ones behind it.
class ThreadPool {
  public:
    /// threads >= 1 in all, the caller included.
    explicit ThreadPool(int threads);
    ~ThreadPool();
    ThreadPool(const ThreadPool&) = delete;
    ThreadPool& operator=(const ThreadPool&) = delete;

    int thread_count() const { return static_cast<int>(threads_.size()) + 1; }

    /// Runs task(i, i + 1, worker, context) for every i in [0, item_count) and returns when
    /// all have finished. Worker 0 is the caller. Not reentrant.
    void run(TaskCallback* task, int item_count, void* context);

  private:
    void serve(int worker);
    void claim_items(int worker);

    std::vector<std::thread> threads_;
    std::mutex mutex_;
    std::condition_variable wake_;
    std::condition_variable done_;
    // The task being run, written under mutex_ before the generation moves on.
    TaskCallback* task_ = nullptr;
    void* context_ = nullptr;
    int item_count_ = 0;
    std::atomic<int> next_item_{0};
    std::uint64_t generation_ = 0;  // counts the tasks started; a change wakes the workers
    int busy_ = 0;                  // workers not yet done with this generation
    bool stopping_ = false;
};

}  // namespace trackphys::detail
