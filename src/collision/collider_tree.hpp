#pragma once

// The top-level tree of a StaticWorld over its colliders' boxes (private), so that a query
// visits O(log n) colliders' boxes instead of all n.
//
// The tree splits ranges of collider ids, never reordering them: a subtree holds the
// colliders [begin, end), its lanes consecutive parts of that range in order. A depth-first
// visit, lanes in order, therefore meets colliders in id order, which the world's queries
// promise (query_aabb reports colliders in id order, raycast gives ties to the lower id)
// without a sort or a buffer. Colliders come in spatial order in practice (a track's chunks
// in driving order, a mesh's cells row by row), so id ranges are compact; the split point
// of each range is the one of least surface-area cost, as for the BVH. Any order stays
// correct, only slower.
//
// Nodes are eight-wide, their lane boxes in float rounded outward, as the colliders' own
// BVH nodes (bvh_lanes.hpp tests them four lanes at a time): a lane is an inner node or a
// single collider, so a map of thousands of small colliders is a few levels deep and each
// collider's box is tested in its parent's lanes, with no load of its own. A lane box holds
// its colliders' exact boxes, so its test never loses one; a collider lane that passes is
// then tested with the collider's exact double box, which keeps every answer what the loop
// over all colliders gives.

#include <bit>
#include <cstdint>
#include <span>
#include <vector>

#include "bvh_lanes.hpp"
#include "trackphys/geometry/aabb.hpp"

namespace trackphys::collision_detail {

class ColliderTree {
  public:
    static constexpr int kWidth = 8;
    /// Deepest binary level of the build (root 0): surface-area splits down to depth 24,
    /// then halving splits, so up to 2^32 colliders fit. An eight-wide node is at least one
    /// binary level below its parent, so a traversal stack of kMaxStack entries suffices.
    static constexpr int kMaxDepth = 24 + 32;
    static constexpr int kMaxStack = (kWidth - 1) * kMaxDepth + kWidth;

    /// Builds the tree over `boxes` (index = collider id; empty boxes allowed).
    void build(std::span<const Aabb> boxes);
    bool empty() const { return nodes_.empty(); }

    /// Calls visit(id), in increasing id, for every collider whose box overlaps `box`, and
    /// for the rare other one whose box rounded outward to float touches it (a caller that
    /// needs the exact answer tests the collider's box; a collider's own queries give
    /// nothing there, so the world's box query need not).
    template <class Visit>
    void visit_overlapping(const Aabb& box, Visit&& visit) const {
        if (nodes_.empty()) return;
        FloatBox outward, inward;
        round_both_ways(box, outward, inward);
        const QueryLanes q(outward, inward);
        visit_lanes([&](const Node& n) { return may_overlap(BoxLanes::of(n), q); }, visit);
    }

    /// Depth-first, lanes in order, over the lanes `enter` accepts (called with each lane's
    /// box and each collider's exact box), calling visit(id) for each accepted collider in
    /// increasing id. `enter` may depend on what visit did before (a ray's shrinking limit),
    /// and must be monotone in the box (a larger box accepted whenever a smaller one is):
    /// a lane is tested when its node is reached, a collider's exact box when the collider
    /// is, after every lower id was visited.
    template <class Enter, class Visit>
    void visit_nodes(Enter&& enter, std::span<const Aabb> boxes, Visit&& visit) const {
        if (nodes_.empty()) return;
        visit_lanes(
            [&](const Node& n) {
                unsigned accepted = 0;
                for (int i = 0; i < kWidth; ++i)
                    if (n.min[0][i] <= n.max[0][i] && enter(lane_box(n, i))) accepted |= 1u << i;
                return accepted;
            },
            [&](std::uint32_t id) {
                if (!boxes[id].empty() && enter(boxes[id])) visit(id);
            });
    }

  private:
    struct alignas(64) Node {
        float min[3][kWidth];          ///< 96 bytes: min[axis][lane] (m), rounded down
        float max[3][kWidth];          ///< 96 bytes: max[axis][lane] (m), rounded up
        std::uint32_t index[kWidth];   ///< 32 bytes: a collider id or a node index
        std::uint32_t collider_lanes;  ///<  4 bytes: bit i: lane i is a collider
        // An unused lane has NaN bounds: no test accepts it.
    };
    static_assert(sizeof(Node) == 256, "ColliderTree::Node is 256 bytes: four cache lines");
    static_assert(kWidth == BvhNode::kWidth, "the lanes are tested as BvhNode lanes are");

    // The binary tree the build splits first; its levels are then packed eight lanes wide.
    struct BinaryNode {
        Aabb box;  // union of the range's boxes
        std::uint32_t begin, end;
        std::uint32_t left;  // left child (right = left + 1), 0 for a single collider
    };

    static Aabb lane_box(const Node& n, int i) {
        return {{n.min[0][i], n.min[1][i], n.min[2][i]}, {n.max[0][i], n.max[1][i], n.max[2][i]}};
    }

    // Pops nodes from the root on, pushing each node's lanes that `accept_lanes` (node ->
    // lane mask) accepts, last lane first, so lanes are taken in order.
    template <class AcceptLanes, class Visit>
    void visit_lanes(AcceptLanes&& accept_lanes, Visit&& visit) const {
        struct Entry {
            std::uint32_t index;
            bool collider;
        };
        Entry stack[kMaxStack];
        int top = 0;
        stack[top++] = {0, false};
        while (top > 0) {
            const Entry e = stack[--top];
            if (e.collider) {
                visit(e.index);
                continue;
            }
            const Node& n = nodes_[e.index];
            for (unsigned m = accept_lanes(n); m != 0;) {
                const int i = 31 - std::countl_zero(m);
                m &= ~(1u << i);
                stack[top++] = {n.index[i], ((n.collider_lanes >> i) & 1u) != 0};
            }
        }
    }

    void build_binary(std::uint32_t index, std::span<const Aabb> boxes, int depth);
    std::uint32_t pack(std::uint32_t binary);

    std::vector<Node> nodes_;
    std::vector<BinaryNode> binary_;     // build scratch
    std::vector<Aabb> prefix_, suffix_;  // build scratch
};

}  // namespace trackphys::collision_detail
