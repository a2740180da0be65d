#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "trackphys/geometry/aabb.hpp"

namespace trackphys::detail {

/// Two cars whose update boxes overlap, by index, a < b.
struct CarPair {
    std::uint32_t a;
    std::uint32_t b;
};

/// The broad phase between cars: which cars may touch during an update, grouped into
/// islands. Cars whose update boxes (car_update_box) do not overlap cannot meet during the
/// update; an island is a set of cars joined by overlapping boxes, directly or through
/// others, and no car of it can touch a car of another island. So an island's cars step
/// together, and different islands can run on different threads.
///
/// The order is canonical, a function of the boxes alone: islands by their smallest car
/// index, cars and pairs in index order within each. Every buffer is kept, so a steady
/// field of cars finds its islands without allocating.
class CarIslands {
  public:
    /// Sort-and-sweep along x (boxes sorted by min.x; each box against those still open),
    /// then union-find over the overlapping pairs.
    void build(std::span<const Aabb> boxes);

    std::size_t island_count() const { return car_begin_.size() - 1; }
    /// The cars of island i, in index order.
    std::span<const std::uint32_t> cars(std::size_t i) const {
        return std::span(cars_).subspan(car_begin_[i], car_begin_[i + 1] - car_begin_[i]);
    }
    /// The overlapping pairs of island i, ordered by (a, b).
    std::span<const CarPair> pairs(std::size_t i) const {
        return std::span(pairs_).subspan(pair_begin_[i], pair_begin_[i + 1] - pair_begin_[i]);
    }
    /// Every overlapping pair, over all islands: island i's from first_pair(i) on.
    std::span<const CarPair> all_pairs() const { return pairs_; }
    std::size_t pair_count() const { return pairs_.size(); }
    /// Where island i's pairs start in all_pairs().
    std::size_t first_pair(std::size_t i) const { return pair_begin_[i]; }

  private:
    std::uint32_t root(std::uint32_t car);

    std::vector<std::uint32_t> by_min_x_;  // car indices, the sweep order
    std::vector<std::uint32_t> open_;      // boxes the sweep has not passed yet
    std::vector<std::uint32_t> parent_;    // union-find forest
    std::vector<std::uint32_t> island_of_;
    std::vector<std::uint32_t> cars_;
    std::vector<std::size_t> car_begin_{0};
    std::vector<std::size_t> cursor_;  // where each island's next car goes
    std::vector<CarPair> pairs_;
    std::vector<std::size_t> pair_begin_{0};
};

}  // namespace trackphys::detail
