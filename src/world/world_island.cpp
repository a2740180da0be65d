// World::step_island: one update of an island of cars (see World's class notes).

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "profile/phase_stopwatch.hpp"
#include "trackphys/world/world.hpp"
#include "world/car_pair_contact.hpp"
#include "world/car_scratch.hpp"
#include "world/car_slot.hpp"
#include "world/update_work.hpp"

namespace trackphys {

// A lone car keeps the loop of a world without other cars, bit for bit. Cars that may
// meet run the same loop in lockstep: each sub-step finds every car's road contacts from
// the same instant, then the contacts between cars push them (touch_cars), then each car
// integrates; so both cars of a pair feel their contact in the same sub-step.
void World::step_island(std::size_t island, WorkerScratch& scratch, PhaseStopwatch& watch) {
    UpdateWork& work = *work_;
    const std::span<const std::uint32_t> cars = work.islands.cars(island);
    // Each car's working memory, in the worker's scratch.
    for (std::size_t k = 0; k < cars.size(); ++k) {
        CarSlot& slot = cars_[cars[k]];
        scratch.cars[k].start_car(slot.car, slot.empty_lists);
        slot.scratch = &scratch.cars[k];
        slot.start_hits();
    }
    if (cars.size() == 1) {
        update_car(cars_[cars[0]], work.boxes[cars[0]], watch);
        return;
    }
    const std::span<const detail::CarPair> pairs = work.islands.pairs(island);
    const std::size_t first_pair = work.islands.first_pair(island);
    UpdateProfile& profile = watch.profile();
    const double h = settings_.substep_dt();

    for (const std::uint32_t i : cars) begin_update(cars_[i], work.boxes[i], watch);
    for (int step = 0; step < settings_.steps; ++step) {
        for (const std::uint32_t i : cars)
            list_step_candidates(cars_[i], settings_.steps - step, watch);
        for (int s = 0; s < settings_.substeps; ++s) {
            // Every ellipsoid is placed for this sub-step: the pairs below test them all.
            for (const std::uint32_t i : cars) {
                if (s > 0) place_ellipsoids(cars_[i], true);
                find_contacts(cars_[i], watch);
                cars_[i].pushed = false;
            }
            for (std::size_t p = 0; p < pairs.size(); ++p) {
                const detail::CarPair& pair = pairs[p];
                CarSlot& a = cars_[pair.a];
                CarSlot& b = cars_[pair.b];
                const detail::CarPairTouch touch =
                    detail::touch_cars(a.car, a.scratch->placed, b.car, b.scratch->placed, h);
                profile.car_pair_tests += touch.exact_tests;
                work.touches.record(first_pair + p, touch);
                // Only an overlap pushes.
                if (touch.deepest > 0.0) a.pushed = b.pushed = true;
                profile.car_contacts += touch.deepest > 0.0;
                profile.max_car_penetration = std::max(profile.max_car_penetration, touch.deepest);
            }
            watch.lap(Phase::exact);
            // A push from another car can change a car's velocity by more than the step's
            // lists allow for: check their cover again (a query only when it fails). A car
            // nobody pushed is a lone car's case, whose lists hold for the whole step.
            for (const std::uint32_t i : cars)
                if (cars_[i].pushed) list_step_candidates(cars_[i], settings_.steps - step, watch);
            for (const std::uint32_t i : cars) advance(cars_[i], watch);
        }
    }
}

}  // namespace trackphys
