#pragma once

#include <algorithm>
#include <cstddef>
#include <exception>
#include <memory>
#include <vector>

#include "trackphys/geometry/aabb.hpp"
#include "trackphys/geometry/ellipsoid.hpp"
#include "trackphys/profile/update_profile.hpp"
#include "trackphys/world/contact_events.hpp"
#include "trackphys/world/world.hpp"
#include "world/car_islands.hpp"
#include "world/car_scratch.hpp"
#include "world/car_touches.hpp"
#include "world/thread_pool.hpp"

namespace trackphys {

// A worker's scratch for each car of the island it is updating: a car's CarSlot::scratch
// points at its own during its update.
struct World::WorkerScratch {
    // One for each car of the field (set_cars), each grown to the room any of them has needed
    // (grow_alike): the first scratch serves every lone car and is warm within a few updates,
    // the others serve islands of cars, rarer, and would otherwise first grow in a steady state.
    void set_cars(std::size_t count, std::size_t ellipsoids) {
        cars.resize(count);
        if (list_room.size() < ellipsoids) list_room.resize(ellipsoids, 0);
        // make_room reserves every list of list_room, which may be longer than this field's
        // cars need (a larger car earlier).
        for (CarScratch& car : cars) car.reserve(list_room.size());
        make_room();
    }
    // After an island of `used` cars: if one of its scratches grew, all grow alike.
    void grow_alike(std::size_t used) {
        bool grown = false;
        for (std::size_t k = 0; k < used; ++k) {
            const CarScratch& car = cars[k];
            grown |= car.kept.capacity() > kept_room;
            kept_room = std::max(kept_room, car.kept.capacity());
            for (std::size_t i = 0; i < car.listed.size(); ++i) {
                grown |= car.listed[i].capacity() > list_room[i];
                list_room[i] = std::max(list_room[i], car.listed[i].capacity());
            }
        }
        if (grown) make_room();
    }
    void make_room() {
        for (CarScratch& car : cars) {
            car.kept.reserve(kept_room);
            for (std::size_t i = 0; i < list_room.size(); ++i) car.lists[i].reserve(list_room[i]);
        }
    }

    // The most listed triangles a car's lists together have held.
    std::size_t listed_room() const {
        std::size_t room = 0;
        for (const std::size_t r : list_room) room += r;
        return room;
    }

    std::vector<CarScratch> cars;
    std::vector<std::size_t> list_room;  // per ellipsoid index: the most candidates listed
    std::size_t kept_room = 0;           // the most survivors of a sub-step
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
    // Per worker, kept between updates (only ever grown) so that its scratch keeps its heap
    // blocks: one for each car of the field, each for the most ellipsoids a car has.
    std::vector<WorkerScratch> worker_scratch;
    std::size_t scratch_cars = 0;  // the cars they were made for
    // The room every car's CarSlot::DrawnLists has: the most listed triangles and survivors
    // any worker's scratch has held, so that copying them allocates nothing once warm.
    std::size_t drawn_listed_room = 0;
    std::size_t drawn_kept_room = 0;
    // The contact events: the car pairs' (one record per pair, written by its island) and
    // the body hits gathered from the cars' slots after the islands ran.
    detail::CarTouches touches;
    std::vector<BodyHitEvent> body_hits;
    // Per island: what stopped its update, rethrown after all islands ran.
    std::vector<std::exception_ptr> errors;
    std::unique_ptr<detail::ThreadPool> pool;  // started at the first update with 2 islands
    TraceRecorder* trace = nullptr;            // this update's, when it runs on one thread
};

}  // namespace trackphys
