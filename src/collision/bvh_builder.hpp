#pragma once

// The binned-SAH builder behind StaticCollider (private). It only sees boxes: the collider
// turns triangles into outward-rounded float boxes (float_bounds.hpp), the builder returns
// the eight-wide nodes and the leaf order, and the collider permutes its triangle data into
// that order.

#include <cstdint>
#include <vector>

#include "float_bounds.hpp"
#include "trackphys/detail/bvh_node.hpp"
#include "trackphys/geometry/aabb.hpp"

namespace trackphys::collision_detail {

/// A float box padded to four lanes (lane 3 is 0), so that box unions compile to
/// four-wide min/max. 32 bytes.
struct Box4 {
    float lo[4];
    float hi[4];
};
static_assert(sizeof(Box4) == 32);

/// One primitive to build over: its box and its index in the caller's list. 36 bytes.
struct BuildPrimitive {
    Box4 box;
    std::uint32_t index;

    BuildPrimitive() = default;
    BuildPrimitive(const FloatBox& b, std::uint32_t i)
        : box{{b.min[0], b.min[1], b.min[2], 0.0f}, {b.max[0], b.max[1], b.max[2], 0.0f}},
          index(i) {}
};
static_assert(sizeof(BuildPrimitive) == 36);

/// Most primitives in a leaf of the binary SAH tree (bvh_builder.cpp says why 32).
inline constexpr std::uint32_t kMaxLeafSize = 32;
/// Most primitives in a leaf lane of the wide tree: the collapse turns a binary subtree of
/// at most this many into one leaf lane, its primitives in the order of its SAH leaves.
/// Queries test a leaf lane's slot boxes eight at a time in that order, so neighbouring
/// blocks stay tight, and a block test costs much less than a node visit (a dependent
/// load and its branches): default-track car boxes, in driving order or random, are faster
/// than with lanes of one SAH leaf; larger lanes gain nothing, and far larger ones lose.
inline constexpr std::uint32_t kMaxLeafLaneSize = 96;

/// Deepest a built tree gets: SAH splits up to kMaxSahDepth, then median splits that halve
/// the count (at most 31 more levels); the eight-wide tree is never deeper than the binary
/// one it is collapsed from, and queries size their fixed stacks from this.
inline constexpr int kMaxSahDepth = 48;
inline constexpr int kMaxTreeDepth = kMaxSahDepth + 32;
/// Most entries a depth-first traversal of the wide tree keeps pending: each level down
/// leaves at most kWidth - 1 siblings behind, plus the children of the last node.
inline constexpr int kMaxTraversalStack = (BvhNode::kWidth - 1) * kMaxTreeDepth + BvhNode::kWidth;

struct BuiltBvh {
    std::vector<BvhNode> nodes;        ///< eight-wide, root at 0
    std::vector<std::uint32_t> order;  ///< leaf slot -> index of the primitive given
};

/// Builds the tree: a binary tree by binned SAH on centroids, all three axes, up to 16 bins
/// (nodes above ~16k primitives bin a strided sample), leaves of up to kMaxLeafSize, then
/// collapsed into eight-wide nodes (each takes its binary node's two children and keeps
/// opening the inner child of largest area until it has eight; subtrees of up to
/// kMaxLeafLaneSize primitives stay whole, as leaf lanes). Single-threaded and
/// deterministic: the same primitives give the same tree. Empty input -> no nodes.
BuiltBvh build_bvh(std::vector<BuildPrimitive> primitives);

}  // namespace trackphys::collision_detail
