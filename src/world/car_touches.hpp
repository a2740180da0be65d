#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "trackphys/world/contact_events.hpp"
#include "trackphys/world/world_snapshot.hpp"
#include "world/car_islands.hpp"
#include "world/car_pair_contact.hpp"

namespace trackphys::detail {

/// Turns the sub-steps' touches between cars into begin and end events
/// (docs/design.md#contact-events). Each update gets one record per pair of overlapping
/// update boxes (CarIslands::all_pairs), which only that pair's island writes, so islands on
/// different threads write different records; finish() then compares the pairs touched with
/// those touching at the end of the last update, in (a, b) order, whatever ran where.
/// Every buffer is kept: a steady field allocates nothing.
class CarTouches {
  public:
    /// Before the islands run: a blank record for each of the update's `pairs`.
    void start_update(std::size_t pairs);

    /// One sub-step of pair `index` of CarIslands::all_pairs().
    void record(std::size_t index, const CarPairTouch& touch) {
        PairRecord& r = records_[index];
        r.touching_at_end = touch.deepest > 0.0;
        if (!r.touching_at_end) return;
        r.last = {0, 0, touch.deepest_a, touch.deepest_b, touch.deepest_contact};
        if (!r.touched) {
            r.touched = true;
            r.first = touch.deepest_contact;
            r.approach_speed = touch.approach_speed;
        }
        if (touch.deepest > r.deepest) r.deepest = touch.deepest;
    }

    /// After the islands ran over `pairs` (the update's CarIslands::all_pairs()): the
    /// update's events, and the pairs touching at its end for the next one.
    void finish(std::span<const CarPair> pairs);

    /// Car `car` left the world: its touches are forgotten without events, the cars after it
    /// move down one; the last update's events and contacts are dropped (their indices are
    /// stale).
    void remove_car(std::uint32_t car);
    /// Car `car` was moved (World::teleport_car): the last update's contacts of its pairs are
    /// dropped, as its road contacts are; its touches go on.
    void forget_contacts_of(std::uint32_t car);
    /// Pair `index` of CarIslands::all_pairs() did not touch during this update after all: a
    /// car of it was reset to where the update began (World's reset policy), so the pair
    /// ends if it was touching, and begins again at the next update that finds it touching.
    void undo(std::size_t index) { records_[index] = PairRecord{}; }

    /// The pairs touching at the end of the last update, by (car_a, car_b), into `into`
    /// with room for as many as this world's lists: a kept snapshot allocates once.
    void save(std::vector<CarTouchSnapshot>& into) const;
    /// A restored world: `touching` (checked by WorldSnapshot::validate) replaces the list,
    /// the last update's events and contacts are dropped.
    void restore(std::span<const CarTouchSnapshot> touching);

    std::span<const CarTouchBeginEvent> begins() const { return begins_; }
    std::span<const CarTouchEndEvent> ends() const { return ends_; }
    /// The pairs touching at the last sub-step of the last update, by (car_a, car_b).
    std::span<const CarPairContact> contacts() const { return contacts_; }

  private:
    struct PairRecord {
        bool touched = false;          // at any sub-step of the update
        bool touching_at_end = false;  // at its last sub-step
        double deepest = 0.0;          // m, over the update
        Contact first{0.0, glm::dvec3(0.0, 1.0, 0.0), glm::dvec3(0.0)};  // first sub-step's
        double approach_speed = 0.0;  // m/s, at the first sub-step
        CarPairContact last;          // the last sub-step's, when touching_at_end
    };
    std::size_t room_ = 0;                // pairs every list has room for
    std::vector<PairRecord> records_;     // per pair of this update
    std::vector<std::uint32_t> touched_;  // this update's touched records, by (a, b)
    // At the end of the last update, by (a, b), each with its deepest overlap since it began.
    std::vector<CarTouchSnapshot> touching_;
    std::vector<CarTouchSnapshot> next_touching_;
    std::vector<CarTouchBeginEvent> begins_;
    std::vector<CarTouchEndEvent> ends_;
    std::vector<CarPairContact> contacts_;
};

}  // namespace trackphys::detail
