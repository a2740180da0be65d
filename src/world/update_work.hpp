#pragma once

#include <cstddef>
#include <exception>
#include <memory>
#include <vector>

#include "trackphys/geometry/aabb.hpp"
#include "trackphys/geometry/ellipsoid.hpp"
#include "trackphys/profile/update_profile.hpp"
#include "trackphys/world/world.hpp"
#include "world/car_islands.hpp"
#include "world/thread_pool.hpp"

namespace trackphys {

// A worker's placed ellipsoids, one set per car of the island it is updating: a car's
// CarSlot::placed points into its set during its update. What they hold is dead between
// updates (each step places every ellipsoid before anything reads it), so a worker's sets,
// rewritten by every car it updates, stay in its cache, where a set in each car's slot would
// be written cold at each car's update of a big field.
struct World::WorkerScratch {
    std::vector<std::vector<Ellipsoid>> placed;
};

// What World::update works with besides the cars, kept between updates so a steady state
// allocates nothing.
struct World::UpdateWork {
    std::vector<Aabb> boxes;  // per car: car_update_box at the start of the update
    detail::CarIslands islands;
    // Island indices, largest first: the order they are handed out in (results do not
    // depend on it; the long ones starting first keeps the threads' ends close). On one
    // worker, every other update backwards (run_islands).
    std::vector<std::size_t> schedule;
    // Per worker, a cache line or more apart: every sub-step bumps the counts, and two
    // workers writing one line would hand it back and forth between their cores.
    struct alignas(64) WorkerProfile {
        UpdateProfile profile;
    };
    std::vector<WorkerProfile> worker_profiles;
    // Per worker, kept between updates (only ever grown) so that its sets keep their heap
    // blocks: a set for each car of the field, each as long as the most ellipsoids a car has.
    std::vector<WorkerScratch> worker_scratch;
    std::size_t scratch_cars = 0;  // the cars they were made for
    // Per island: what stopped its update, rethrown after all islands ran.
    std::vector<std::exception_ptr> errors;
    std::unique_ptr<detail::ThreadPool> pool;  // started at the first update with 2 islands
    TraceRecorder* trace = nullptr;            // this update's, when it runs on one thread
};

}  // namespace trackphys
