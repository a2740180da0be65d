#include "world/thread_pool.hpp"

namespace trackphys::detail {

ThreadPool::ThreadPool(int threads) {
    for (int worker = 1; worker < threads; ++worker)
        threads_.emplace_back([this, worker] { serve(worker); });
}

ThreadPool::~ThreadPool() {
    {
        std::lock_guard lock(mutex_);
        stopping_ = true;
    }
    wake_.notify_all();
    for (std::thread& thread : threads_) thread.join();
}

void ThreadPool::run(TaskCallback* task, int item_count, void* context) {
    {
        std::lock_guard lock(mutex_);
        task_ = task;
        context_ = context;
        item_count_ = item_count;
        next_item_.store(0, std::memory_order_relaxed);
        busy_ = static_cast<int>(threads_.size());
        ++generation_;
    }
    wake_.notify_all();
    claim_items(0);
    // Every worker must leave this generation before the next run rewrites the task.
    std::unique_lock lock(mutex_);
    done_.wait(lock, [this] { return busy_ == 0; });
}

void ThreadPool::serve(int worker) {
    std::uint64_t seen = 0;
    for (;;) {
        {
            std::unique_lock lock(mutex_);
            wake_.wait(lock, [&] { return stopping_ || generation_ != seen; });
            if (stopping_) return;
            seen = generation_;
        }
        claim_items(worker);
        {
            std::lock_guard lock(mutex_);
            if (--busy_ == 0) done_.notify_one();
        }
    }
}

void ThreadPool::claim_items(int worker) {
    for (int item = next_item_.fetch_add(1, std::memory_order_relaxed); item < item_count_;
         item = next_item_.fetch_add(1, std::memory_order_relaxed))
        task_(item, item + 1, worker, context_);
}

}  // namespace trackphys::detail
