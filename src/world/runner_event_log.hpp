#pragma once

// PhysicsRunner's event log (internal): after each update the physics thread appends the
// world's contact events and new resets, in the runner's car numbers, and the game thread
// takes them, both under one mutex (a few appends an update, one swap a take).

#include <cstddef>
#include <cstdint>
#include <mutex>
#include <span>
#include <vector>

#include "trackphys/world/runner_events.hpp"
#include "trackphys/world/world.hpp"

namespace trackphys::detail {

class RunnerEventLog {
  public:
    /// Before a run (no physics thread): the runner numbers of the world's cars
    /// (world_index[r] for each r not removed) and each car's resets so far, so that a
    /// restored or edited world reports only what its updates reset.
    void start(const World& world, std::span<const std::size_t> world_index,
               std::span<const std::uint8_t> removed);
    /// After each update (physics thread): keeps its events when `keep`, and follows the
    /// cars' reset counts either way, so that a reset is reported at its own update only.
    void collect(const World& world, std::span<const std::size_t> world_index,
                 std::span<const std::uint8_t> removed, bool keep);
    /// Swaps the events kept so far into `out`, emptied first (any thread).
    void take(RunnerEvents& out);

  private:
    std::mutex mutex_;
    RunnerEvents kept_;                           // guarded by mutex_
    std::vector<std::uint32_t> runner_of_world_;  // per world index, the runner's number
    std::vector<std::uint64_t> resets_seen_;      // per runner number
    std::vector<std::uint32_t> resets_now_;       // the cars reset by the last update
};

}  // namespace trackphys::detail
