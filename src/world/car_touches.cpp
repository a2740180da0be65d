#include "world/car_touches.hpp"

#include <algorithm>
#include <utility>

namespace trackphys::detail {

// Every list is bounded by the pairs of one or two updates (an update's ends by the pairs
// touching before it and those touched during it): room for twice the most pairs yet, grown
// by doubling, so a field whose pairs creep up reserves a few times and then no more.
void CarTouches::start_update(std::size_t pairs) {
    if (pairs > room_) {
        room_ = std::max(pairs, 2 * room_);
        records_.reserve(room_);
        touched_.reserve(room_);
        touching_.reserve(room_);
        next_touching_.reserve(room_);
        begins_.reserve(room_);
        ends_.reserve(2 * room_);
        contacts_.reserve(room_);
    }
    records_.assign(pairs, PairRecord{});
    begins_.clear();
    ends_.clear();
    contacts_.clear();
}

// A merge of two lists sorted by (a, b): the pairs touched during this update and those
// touching at the end of the last one. A pair of the last list alone has come apart (its
// boxes may not even overlap any more); one of this update's alone began; one of both went
// on, and ends if it is apart at the last sub-step.
void CarTouches::finish(std::span<const CarPair> pairs) {
    touched_.clear();
    for (std::uint32_t i = 0; i < records_.size(); ++i)
        if (records_[i].touched) touched_.push_back(i);
    const auto key = [&](std::uint32_t i) { return std::pair(pairs[i].a, pairs[i].b); };
    std::sort(touched_.begin(), touched_.end(),
              [&](std::uint32_t i, std::uint32_t j) { return key(i) < key(j); });

    next_touching_.clear();
    std::size_t last = 0;
    const auto came_apart = [&](const CarTouchSnapshot& t) {
        ends_.push_back({t.car_a, t.car_b, t.deepest});
    };
    for (const std::uint32_t i : touched_) {
        const auto [a, b] = key(i);
        for (; last < touching_.size() &&
               std::pair(touching_[last].car_a, touching_[last].car_b) < key(i);
             ++last)
            came_apart(touching_[last]);
        const PairRecord& r = records_[i];
        CarTouchSnapshot now{a, b, r.deepest};
        const bool went_on =
            last < touching_.size() && touching_[last].car_a == a && touching_[last].car_b == b;
        if (went_on)
            now.deepest = std::max(now.deepest, touching_[last++].deepest);
        else
            begins_.push_back(
                {a, b, r.first.point, r.first.normal, r.first.depth, r.approach_speed});
        if (r.touching_at_end) {
            next_touching_.push_back(now);
            CarPairContact& contact = contacts_.emplace_back(r.last);
            contact.car_a = a;
            contact.car_b = b;
        } else {
            came_apart(now);
        }
    }
    for (; last < touching_.size(); ++last) came_apart(touching_[last]);
    std::swap(touching_, next_touching_);
}

void CarTouches::remove_car(std::uint32_t car) {
    std::erase_if(touching_,
                  [car](const CarTouchSnapshot& t) { return t.car_a == car || t.car_b == car; });
    // Moving every index past `car` down one keeps the (a, b) order.
    for (CarTouchSnapshot& t : touching_) {
        t.car_a -= t.car_a > car;
        t.car_b -= t.car_b > car;
    }
    begins_.clear();
    ends_.clear();
    contacts_.clear();
}

void CarTouches::forget_contacts_of(std::uint32_t car) {
    std::erase_if(contacts_,
                  [car](const CarPairContact& c) { return c.car_a == car || c.car_b == car; });
}

void CarTouches::save(std::vector<CarTouchSnapshot>& into) const {
    into.reserve(room_);
    into.assign(touching_.begin(), touching_.end());
}

void CarTouches::restore(std::span<const CarTouchSnapshot> touching) {
    touching_.assign(touching.begin(), touching.end());
    begins_.clear();
    ends_.clear();
    contacts_.clear();
}

}  // namespace trackphys::detail
