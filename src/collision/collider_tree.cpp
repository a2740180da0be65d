#include "collider_tree.hpp"

#include <limits>

namespace trackphys::collision_detail {
namespace {

// Surface-area splits above this depth, halving ones below (see kMaxDepth).
constexpr int kCostDepth = 24;

}  // namespace

void ColliderTree::build(std::span<const Aabb> boxes) {
    nodes_.clear();
    if (boxes.empty()) return;
    prefix_.resize(boxes.size());
    suffix_.resize(boxes.size());
    binary_.reserve(2 * boxes.size());
    binary_.push_back({{}, 0, static_cast<std::uint32_t>(boxes.size()), 0});
    build_binary(0, boxes, 0);
    prefix_ = {};
    suffix_ = {};
    pack(0);
    nodes_.shrink_to_fit();
    binary_ = {};
}

void ColliderTree::build_binary(std::uint32_t index, std::span<const Aabb> boxes, int depth) {
    const std::uint32_t begin = binary_[index].begin, end = binary_[index].end;
    Aabb box;
    for (std::uint32_t i = begin; i < end; ++i) box.expand(boxes[i]);
    binary_[index].box = box;
    if (end - begin == 1) return;

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
    const auto left = static_cast<std::uint32_t>(binary_.size());
    binary_.push_back({{}, begin, split, 0});
    binary_.push_back({{}, split, end, 0});
    binary_[index].left = left;
    build_binary(left, boxes, depth + 1);
    build_binary(left + 1, boxes, depth + 1);
}

// The eight-wide node of binary node `binary`: its two children, then, while there is room,
// lanes replaced in place by their two children (so the lanes stay in id order): first the
// lane of most colliders while one has more than a node holds, then, smallest first, lanes
// whose colliders all fit in the node as collider lanes (a node of their own would hold a
// few lanes only). Each remaining inner lane becomes a node of its own. Returns the node's
// index.
std::uint32_t ColliderTree::pack(std::uint32_t binary) {
    std::uint32_t lanes[kWidth];
    int count = 0;
    if (binary_[binary].left == 0) {
        lanes[count++] = binary;  // a single collider: the root of a one-collider world
    } else {
        lanes[count++] = binary_[binary].left;
        lanes[count++] = binary_[binary].left + 1;
    }
    const auto colliders = [&](int i) { return binary_[lanes[i]].end - binary_[lanes[i]].begin; };
    const auto split = [&](int at) {
        for (int i = count; i > at + 1; --i) lanes[i] = lanes[i - 1];
        lanes[at + 1] = binary_[lanes[at]].left + 1;
        lanes[at] = binary_[lanes[at]].left;
        ++count;
    };
    while (count < kWidth) {
        int largest = 0;
        for (int i = 1; i < count; ++i)
            if (colliders(i) > colliders(largest)) largest = i;
        if (colliders(largest) <= std::uint32_t(kWidth)) break;
        split(largest);
    }
    for (;;) {
        int smallest = -1;
        for (int i = 0; i < count; ++i)
            if (colliders(i) > 1 && (smallest < 0 || colliders(i) < colliders(smallest)))
                smallest = i;
        if (smallest < 0 || count - 1 + int(colliders(smallest)) > kWidth) break;
        const std::uint32_t end = binary_[lanes[smallest]].end;
        for (int i = smallest; i < count && binary_[lanes[i]].end <= end; ++i)
            while (colliders(i) > 1) split(i);
    }

    const auto index = static_cast<std::uint32_t>(nodes_.size());
    nodes_.emplace_back();
    Node node{};
    for (int i = 0; i < kWidth; ++i) {
        for (int a = 0; a < 3; ++a)
            node.min[a][i] = node.max[a][i] = std::numeric_limits<float>::quiet_NaN();
        node.index[i] = 0;
    }
    for (int i = 0; i < count; ++i) {
        const BinaryNode& b = binary_[lanes[i]];
        if (!b.box.empty()) {
            const FloatBox box = outward_float_box(b.box);
            for (int a = 0; a < 3; ++a) {
                node.min[a][i] = box.min[a];
                node.max[a][i] = box.max[a];
            }
        }
        if (b.left == 0) {
            node.index[i] = b.begin;
            node.collider_lanes |= 1u << i;
        } else if (!b.box.empty()) {
            node.index[i] = pack(lanes[i]);
        }
    }
    nodes_[index] = node;
    return index;
}

}  // namespace trackphys::collision_detail
