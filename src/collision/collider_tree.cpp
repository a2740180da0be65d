#include "collider_tree.hpp"

#include <limits>

namespace trackphys::collision_detail {
namespace {

// Colliders in a leaf: a collider's own box test is cheap next to its BVH query.
constexpr std::uint32_t kLeafColliders = 2;
// Surface-area splits above this depth, halving ones below (see kMaxDepth).
constexpr int kCostDepth = 24;

}  // namespace

void ColliderTree::build(std::span<const Aabb> boxes) {
    nodes_.clear();
    if (boxes.empty()) return;
    prefix_.resize(boxes.size());
    suffix_.resize(boxes.size());
    nodes_.reserve(2 * boxes.size() / kLeafColliders + 1);
    nodes_.push_back({{}, 0, static_cast<std::uint32_t>(boxes.size()), 0, 0});
    build_node(0, boxes, 0);
    prefix_ = {};
    suffix_ = {};
}

void ColliderTree::build_node(std::uint32_t index, std::span<const Aabb> boxes, int depth) {
    const std::uint32_t begin = nodes_[index].begin, end = nodes_[index].end;
    Aabb box;
    for (std::uint32_t i = begin; i < end; ++i) box.expand(boxes[i]);
    nodes_[index].box = box;
    if (end - begin <= kLeafColliders) return;

    // The cut of least cost, area(prefix) * its count + area(suffix) * its count; the first
    // of equal ones.
    std::uint32_t split = begin + (end - begin) / 2;
    if (depth < kCostDepth) {
        Aabb grown;
        for (std::uint32_t i = begin; i < end; ++i) {
            grown.expand(boxes[i]);
            prefix_[i] = grown;
        }
        grown = Aabb{};
        for (std::uint32_t i = end; i-- > begin;) {
            grown.expand(boxes[i]);
            suffix_[i] = grown;
        }
        double best = std::numeric_limits<double>::infinity();
        for (std::uint32_t k = begin + 1; k < end; ++k) {
            const double cost = prefix_[k - 1].surface_area() * double(k - begin) +
                                suffix_[k].surface_area() * double(end - k);
            if (cost < best) {
                best = cost;
                split = k;
            }
        }
    }
    const auto left = static_cast<std::uint32_t>(nodes_.size());
    nodes_.push_back({{}, begin, split, 0, 0});
    nodes_.push_back({{}, split, end, 0, 0});
    nodes_[index].left = left;
    build_node(left, boxes, depth + 1);
    build_node(left + 1, boxes, depth + 1);
}

std::size_t ColliderTree::bytes_used() const { return nodes_.capacity() * sizeof(Node); }

}  // namespace trackphys::collision_detail
