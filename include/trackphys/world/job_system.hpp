#pragma once

namespace trackphys {

/// A range of work items, [begin, end), run by worker `worker` (0 <= worker < the job
/// system's worker_count; one worker index is never in use twice at once). task_context
/// is what World passed to enqueue_task.
using TaskCallback = void(int begin, int end, int worker, void* task_context);

/// A game's own job system, plugged into World (in the style of Box2D v3's
/// b2EnqueueTaskCallback / b2FinishTaskCallback). World::update calls enqueue_task once
/// per update with item_count independent items (islands of cars) and min_range, the
/// smallest range worth a job of its own; the job system runs task over ranges that cover
/// every item exactly once, on any of its threads. It returns a handle that World passes
/// to finish_task, which must return only after every range has run; or nullptr when it
/// ran every range already (then finish_task is not called). Results do not depend on how
/// the items are split or in what order they run.
struct JobSystem {
    void* (*enqueue_task)(TaskCallback* task, int item_count, int min_range, void* task_context,
                          void* user_context) = nullptr;
    void (*finish_task)(void* user_task, void* user_context) = nullptr;
    void* user_context = nullptr;  ///< passed back to both callbacks
    /// The worker indices a task may see: 0 .. worker_count - 1. World keeps scratch memory
    /// per index; a task run on an index outside them updates nothing of its range, and
    /// World::update throws trackphys::Error naming the index.
    int worker_count = 1;

    /// Whether a job system is plugged in (both callbacks set).
    bool plugged_in() const { return enqueue_task != nullptr && finish_task != nullptr; }
};

}  // namespace trackphys
