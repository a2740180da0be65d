#pragma once

#include <atomic>
#include <cstdint>
#include <thread>
#include <vector>

#include "trackphys/world/job_system.hpp"

namespace trackphys::detail {

/// World's own workers when no job system is plugged in: threads - 1 threads, and the
/// calling thread, which works too. Items are claimed one at a time from a shared counter,
/// so a large island does not hold up the small ones behind it.
///
/// The hand-offs are where an update's wall clock leaks on a busy machine, so neither side
/// waits for what it does not need: run returns as soon as every item has finished, without
/// waiting for a worker that has not woken up yet (that worker finds the task closed and
/// goes back to sleep), and each side spins for a short while (kSpin) before it sleeps, so a
/// worker that finishes its last island or a run that follows at once costs no wake-up.
class ThreadPool {
  public:
    /// threads >= 1 in all, the caller included. Throws trackphys::Error when the system
    /// cannot start them all (the ones started are joined first).
    explicit ThreadPool(int threads);
    ~ThreadPool();
    ThreadPool(const ThreadPool&) = delete;
    ThreadPool& operator=(const ThreadPool&) = delete;

    int thread_count() const { return static_cast<int>(threads_.size()) + 1; }

    /// Runs task(i, i + 1, worker, context) for every i in [0, item_count) and returns when
    /// all have finished. Worker 0 is the caller. Not reentrant. task must not throw: an
    /// exception leaving it ends the program on every thread alike, the caller's included,
    /// since a half-run task would leave the pool unable to run the next (World's own task
    /// catches each island's error and rethrows it after the run).
    void run(TaskCallback* task, int item_count, void* context);

  private:
    void stop_workers();
    void serve(int worker);
    // Whether the worker joined the open task `task_state` (then it must leave() after).
    bool join(std::uint32_t task_state);
    void leave();
    void claim_items(int worker) noexcept;

    std::vector<std::thread> threads_;
    // The task being run, written by run() while no worker has joined; a worker reads it
    // only after joining an open task.
    TaskCallback* task_ = nullptr;
    void* context_ = nullptr;
    int item_count_ = 0;
    std::atomic<int> next_item_{0};
    std::atomic<int> finished_items_{0};
    // Twice the number of tasks started, plus 1 while the current one is open: a worker
    // wakes on its change and joins only an open task. stopping_ ends the workers.
    std::atomic<std::uint32_t> task_state_{0};
    // Workers inside the open task: run() closes the task, then waits for them to leave
    // before the next run rewrites it.
    std::atomic<int> joined_{0};
    std::atomic<bool> stopping_{false};
};

}  // namespace trackphys::detail
