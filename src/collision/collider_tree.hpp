#pragma once

// The top-level tree of a StaticWorld over its colliders' boxes (private), so that a query
// visits O(log n) colliders' boxes instead of all n.
//
// The tree splits ranges of collider ids, never reordering them: a subtree holds the
// colliders [begin, end), its left child a prefix of that range. A depth-first visit, left
// child first, therefore meets colliders in id order, which the world's queries promise
// (query_aabb reports colliders in id order, raycast gives ties to the lower id) without a
// sort or a buffer. Colliders come in spatial order in practice (a track's chunks in
// driving order, a mesh's cells row by row), so id ranges are compact; the split point of
// each range is the one of least surface-area cost, as for the BVH. Any order stays
// correct, only slower.

#include <cstdint>
#include <span>
#include <vector>

#include "trackphys/geometry/aabb.hpp"

namespace trackphys::collision_detail {

class ColliderTree {
  public:
    /// Deepest node (root 0): surface-area splits down to depth 24, then halving splits,
    /// so a fixed stack of kMaxDepth + 1 holds a traversal for up to 2^32 colliders.
    static constexpr int kMaxDepth = 24 + 32;

    /// Builds the tree over `boxes` (index = collider id; empty boxes allowed).
    void build(std::span<const Aabb> boxes);
    bool empty() const { return nodes_.empty(); }

    /// Calls visit(id) for every collider whose box overlaps `box`, in increasing id.
    template <class Visit>
    void visit_overlapping(std::span<const Aabb> boxes, const Aabb& box, Visit&& visit) const {
        visit_nodes([&](const Aabb& b) { return b.overlaps(box); }, boxes, visit);
    }

    /// Depth-first, left first, over the nodes `enter` accepts (called with each node's box
    /// and each collider's), calling visit(id) for each accepted collider in increasing id.
    /// `enter` may depend on what visit did before (a ray's shrinking limit): a node is
    /// tested when it is reached, after every lower id was visited.
    template <class Enter, class Visit>
    void visit_nodes(Enter&& enter, std::span<const Aabb> boxes, Visit&& visit) const {
        if (nodes_.empty()) return;
        std::uint32_t stack[kMaxDepth + 1];
        int top = 0;
        stack[top++] = 0;
        while (top > 0) {
            const Node& node = nodes_[stack[--top]];
            if (node.box.empty() || !enter(node.box)) continue;
            if (node.left == 0) {
                for (std::uint32_t id = node.begin; id < node.end; ++id)
                    if (!boxes[id].empty() && enter(boxes[id])) visit(id);
                continue;
            }
            stack[top++] = node.left + 1;
            stack[top++] = node.left;
        }
    }

    std::size_t bytes_used() const;

  private:
    struct Node {
        Aabb box;              ///< 48 bytes: union of the range's boxes
        std::uint32_t begin;   ///<  4: first collider id
        std::uint32_t end;     ///<  4: one past the last
        std::uint32_t left;    ///<  4: left child (right = left + 1), 0 for a leaf
        std::uint32_t unused;  ///<  4
    };
    static_assert(sizeof(Node) == 64, "ColliderTree::Node is 64 bytes: one cache line");

    void build_node(std::uint32_t index, std::span<const Aabb> boxes, int depth);

    std::vector<Node> nodes_;
    std::vector<Aabb> prefix_, suffix_;  // build scratch
};

}  // namespace trackphys::collision_detail
