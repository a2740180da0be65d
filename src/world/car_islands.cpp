#include "world/car_islands.hpp"

#include <algorithm>
#include <numeric>

namespace trackphys::detail {

std::uint32_t CarIslands::root(std::uint32_t car) {
    while (parent_[car] != car) {
        parent_[car] = parent_[parent_[car]];  // path halving
        car = parent_[car];
    }
    return car;
}

void CarIslands::build(std::span<const Aabb> boxes) {
    const auto count = static_cast<std::uint32_t>(boxes.size());

    // Sweep: a box meets only boxes that start before it ends along x, so each box is
    // compared with the open boxes whose x range it reaches.
    by_min_x_.resize(count);
    std::iota(by_min_x_.begin(), by_min_x_.end(), 0u);
    std::sort(by_min_x_.begin(), by_min_x_.end(), [&](std::uint32_t i, std::uint32_t j) {
        return boxes[i].min.x < boxes[j].min.x || (boxes[i].min.x == boxes[j].min.x && i < j);
    });
    pairs_.clear();
    open_.clear();
    for (const std::uint32_t car : by_min_x_) {
        const Aabb& box = boxes[car];
        std::erase_if(open_, [&](std::uint32_t other) { return boxes[other].max.x < box.min.x; });
        for (const std::uint32_t other : open_)
            if (box.overlaps(boxes[other]))
                pairs_.push_back({std::min(car, other), std::max(car, other)});
        open_.push_back(car);
    }

    parent_.resize(count);
    std::iota(parent_.begin(), parent_.end(), 0u);
    for (const CarPair& pair : pairs_) parent_[root(pair.a)] = root(pair.b);

    // Islands numbered in order of their smallest car: a car whose root has no island yet
    // opens the next one.
    constexpr std::uint32_t kNone = ~0u;
    island_of_.assign(count, kNone);
    car_begin_.assign(1, 0);
    std::uint32_t islands = 0;
    for (std::uint32_t car = 0; car < count; ++car) {
        std::uint32_t& island = island_of_[root(car)];
        if (island == kNone) {
            island = islands++;
            car_begin_.push_back(0);
        }
        ++car_begin_[island + 1];
    }
    for (std::uint32_t i = 0; i < islands; ++i) car_begin_[i + 1] += car_begin_[i];
    cars_.resize(count);
    // Filling in car order keeps the cars of an island in index order.
    cursor_.assign(car_begin_.begin(), car_begin_.end() - 1);
    for (std::uint32_t car = 0; car < count; ++car) cars_[cursor_[island_of_[root(car)]]++] = car;

    const auto island_of_pair = [&](const CarPair& p) { return island_of_[root(p.a)]; };
    std::sort(pairs_.begin(), pairs_.end(), [&](const CarPair& p, const CarPair& q) {
        const std::uint32_t ip = island_of_pair(p);
        const std::uint32_t iq = island_of_pair(q);
        return ip != iq ? ip < iq : (p.a != q.a ? p.a < q.a : p.b < q.b);
    });
    pair_begin_.assign(islands + 1, 0);
    for (const CarPair& pair : pairs_) ++pair_begin_[island_of_pair(pair) + 1];
    for (std::uint32_t i = 0; i < islands; ++i) pair_begin_[i + 1] += pair_begin_[i];
}

}  // namespace trackphys::detail
