#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "trackphys/collision/look_ahead_list.hpp"
#include "trackphys/collision/mid_phase.hpp"
#include "trackphys/geometry/ellipsoid.hpp"
#include "trackphys/world/world.hpp"

namespace trackphys {

// A car's working memory that is dead between its updates: the placed ellipsoids (each step
// places every ellipsoid before anything reads them), the look-ahead lists (each update
// queries them anew from its own box) and the culled survivors (rebuilt every sub-step).
// A worker keeps one per car of the island it is updating (World::WorkerScratch), rewritten
// by every car it updates, so it stays in the worker's cache, where the same bytes in each
// car's slot would be written cold at each car's update of a big field. What a car carries
// from one update to the next (which of its lists were empty) stays in its slot.
struct World::CarScratch {
    // A candidate that passed the cull, with an upper bound of its penetration depth.
    struct Survivor {
        TriangleRef ref;
        const NormalizedTriangle* frame;  // the mid phase's, valid for the sub-step
        double depth_bound;
    };

    // Room for a car of up to `ellipsoids` ellipsoids, so a steady state allocates nothing.
    void reserve(std::size_t ellipsoids) {
        placed.reserve(ellipsoids);
        if (lists.size() < ellipsoids) {
            lists.resize(ellipsoids);
            listed = {};  // viewed the old lists; start_car views the new
        }
        kept_start.reserve(ellipsoids + 1);
    }

    // Ready for one update of `car`: copies of its body ellipsoids, as placing wants them (it
    // writes what a motion changes, not the radii), and lists that know which of the car's
    // were empty at its last update (bit i of `empty_lists`, LookAheadList::steps_ahead).
    void start_car(const Car& car, std::uint64_t empty_lists) {
        const std::size_t ellipsoids = car.ellipsoid_count();
        placed.clear();
        for (std::size_t i = 0; i < ellipsoids; ++i) placed.push_back(car.body_ellipsoid(i));
        listed = std::span(lists).first(ellipsoids);
        for (std::size_t i = 0; i < ellipsoids; ++i)
            listed[i].start_over(((empty_lists >> i) & 1u) != 0);
        kept.clear();
        kept_start.assign(ellipsoids + 1, 0u);
    }

    // Which of the car's lists were empty, for its next update's start_car.
    std::uint64_t empty_lists() const {
        std::uint64_t bits = 0;
        for (std::size_t i = 0; i < listed.size(); ++i)
            bits |= static_cast<std::uint64_t>(listed[i].was_empty()) << i;
        return bits;
    }

    // Ellipsoid i's survivors of this sub-step's cull, from the buffer and its starts (which
    // find_contacts reads once, as spans).
    static std::span<Survivor> survivors(Survivor* kept, std::span<const std::uint32_t> start,
                                         std::size_t i) {
        return {kept + start[i], kept + start[i + 1]};
    }

    std::vector<Ellipsoid> placed;    // this sub-step (World::place_ellipsoids)
    std::span<LookAheadList> listed;  // per ellipsoid, this step: the front of `lists`
    // Every ellipsoid's culled survivors in one buffer, in ellipsoid order (one block of
    // lines a sub-step rather than a heap block per ellipsoid): see survivors().
    std::vector<Survivor> kept;
    std::vector<std::uint32_t> kept_start;  // ellipsoid i's from kept_start[i] to [i + 1]
    std::vector<LookAheadList> lists;       // as many as the most ellipsoids a car has
};

}  // namespace trackphys
