// The structure checks of a loaded map (docs/tpmap.md#what-loading-verifies): every index
// and range a query follows, verified once in time linear in the arrays, so that queries
// on a map file that passes never read out of bounds, overflow their fixed stacks or loop.
// The checksum catches accidental damage before this runs; these checks stand between a
// crafted file and the queries. They do not re-derive the bounds (a lane box that does not
// hold its triangles makes queries miss them, but never misbehave).

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "collision/bvh_builder.hpp"
#include "map_codec.hpp"
#include "trackphys/error.hpp"

namespace trackphys::detail {
namespace {

constexpr std::uint32_t kNoSlot = std::numeric_limits<std::uint32_t>::max();

[[noreturn]] void fail(const std::string& what) { throw Error(what); }

std::string at(const char* array, std::size_t index) {
    return std::string(array) + " " + std::to_string(index) + ": ";
}

bool is_nan_lane(const BvhNode& n, int i) {
    for (int a = 0; a < 3; ++a)
        if (!std::isnan(n.min[a][i]) || !std::isnan(n.max[a][i])) return false;
    return true;
}

bool is_box_lane(const BvhNode& n, int i) {
    for (int a = 0; a < 3; ++a)
        if (!(n.min[a][i] <= n.max[a][i])) return false;
    return true;
}

// A grid as quantize_query and the raycast use it: a power-of-two scale, an integer base
// small enough that base +- 2^16 stays exact.
bool is_valid_grid(const BvhNodeGrid& g) {
    constexpr std::uint64_t kMantissa = (std::uint64_t{1} << 52) - 1;
    for (int a = 0; a < 3; ++a) {
        const double s = g.inv_step[a], b = g.base[a];
        if (!(std::isnormal(s) && s > 0.0 && (std::bit_cast<std::uint64_t>(s) & kMantissa) == 0))
            return false;
        if (!(std::abs(b) <= 0x1p52 && std::floor(b) == b)) return false;
    }
    return true;
}

}  // namespace

void MapCodec::check_collider(StaticCollider& c) {
    const std::size_t slots = c.slot_vertices_.size();
    if ((slots == 0) != c.nodes_.empty())
        fail("the collider keeps " + std::to_string(slots) + " triangles in " +
             std::to_string(c.nodes_.size()) + " BVH nodes");

    c.bounds_ = Aabb{};
    for (std::size_t v = 0; v < c.vertices_.size(); ++v) {
        const glm::dvec3& p = c.vertices_[v];
        for (int a = 0; a < 3; ++a)
            if (!(std::abs(p[a]) <= StaticCollider::kMaxCoordinate))
                fail(at("vertex", v) + "coordinate " + std::to_string(p[a]) +
                     " is not finite or beyond the collider's limit");
        c.bounds_.expand(p);
    }
    // Kept triangles are not degenerate (the contact code and the frames rely on it).
    for (std::size_t s = 0; s < slots; ++s) {
        const auto& tri = c.slot_vertices_[s];
        for (const std::uint32_t v : tri)
            if (v >= c.vertices_.size())
                fail(at("slot", s) + "vertex index " + std::to_string(v) + " out of range (" +
                     std::to_string(c.vertices_.size()) + " vertices)");
        if (Triangle{c.vertices_[tri[0]], c.vertices_[tri[1]], c.vertices_[tri[2]]}.is_degenerate())
            fail(at("slot", s) + "a degenerate triangle");
    }

    // Slots and kept mesh triangles map one to one.
    std::size_t kept = 0;
    for (std::size_t t = 0; t < c.triangle_to_slot_.size(); ++t) {
        const std::uint32_t s = c.triangle_to_slot_[t];
        if (s == kNoSlot) continue;
        if (s >= slots)
            fail(at("mesh triangle", t) + "slot " + std::to_string(s) + " out of range (" +
                 std::to_string(slots) + " slots)");
        ++kept;
    }
    if (kept != slots)
        fail(std::to_string(kept) + " mesh triangles have a slot, the collider keeps " +
             std::to_string(slots));
    for (std::size_t s = 0; s < slots; ++s) {
        const std::uint32_t t = c.slot_triangle(static_cast<std::uint32_t>(s));
        if (t >= c.triangle_to_slot_.size() || c.triangle_to_slot_[t] != s)
            fail(at("slot", s) + "mesh triangle " + std::to_string(t) + " does not map back to it");
    }

    for (std::size_t g = 0; g < c.grids_.size(); ++g)
        if (!is_valid_grid(c.grids_[g])) fail(at("BVH grid", g) + "not a power-of-two grid");

    // The tree, from the root: every node reached once, no deeper than the traversal stacks
    // allow, each lane's slot range inside its node's and non-empty unless the lane is
    // empty (NaN bounds, which no query hits).
    if (c.nodes_.empty()) return;
    struct Entry {
        std::uint32_t node, begin, end;
        int depth;
    };
    std::vector<char> reached(c.nodes_.size(), 0);
    std::vector<Entry> stack{{0, 0, static_cast<std::uint32_t>(slots), 0}};
    reached[0] = 1;
    std::size_t reached_count = 1;
    while (!stack.empty()) {
        const Entry e = stack.back();
        stack.pop_back();
        const BvhNode& n = c.nodes_[e.node];
        // Messages are built only on failure (these run per node).
        const auto where = [&] { return at("BVH node", e.node); };
        if (e.depth >= collision_detail::kMaxTreeDepth)
            fail(where() + "deeper than " + std::to_string(collision_detail::kMaxTreeDepth));
        if (n.first[0] != e.begin)
            fail(where() + "lane 0 starts at slot " + std::to_string(n.first[0]) + ", not " +
                 std::to_string(e.begin));
        bool has_leaf = false;
        for (int i = 0; i < BvhNode::kWidth; ++i) {
            const auto lane = [&] { return where() + "lane " + std::to_string(i) + ": "; };
            const std::uint32_t first = n.first[i], end = n.end(i, e.end);
            if (!(first <= end && end <= e.end))
                fail(lane() + "slots [" + std::to_string(first) + ", " + std::to_string(end) +
                     ") outside the node's [" + std::to_string(e.begin) + ", " +
                     std::to_string(e.end) + ")");
            if (is_nan_lane(n, i)) {
                if (first != end || n.child[i] != BvhNode::kLeaf)
                    fail(lane() + "an empty lane with slots or a child");
                continue;
            }
            if (!is_box_lane(n, i)) fail(lane() + "bounds neither a box nor empty (NaN)");
            if (first == end) fail(lane() + "a box over no slots");
            if (n.child[i] == BvhNode::kLeaf) {
                if (end - first > collision_detail::kMaxLeafLaneSize)
                    fail(lane() + "a leaf of " + std::to_string(end - first) +
                         " slots, more than " + std::to_string(collision_detail::kMaxLeafLaneSize));
                has_leaf = true;
                continue;
            }
            const std::uint32_t child = n.child[i];
            if (child >= c.nodes_.size())
                fail(lane() + "child " + std::to_string(child) + " out of range (" +
                     std::to_string(c.nodes_.size()) + " nodes)");
            if (reached[child]) fail(lane() + "child " + std::to_string(child) + " reached twice");
            reached[child] = 1;
            ++reached_count;
            stack.push_back({child, first, end, e.depth + 1});
        }
        if (has_leaf && c.node_grid_[e.node] >= c.grids_.size())
            fail(where() + "grid " + std::to_string(c.node_grid_[e.node]) + " out of range (" +
                 std::to_string(c.grids_.size()) + " grids)");
    }
    if (reached_count != c.nodes_.size())
        fail(std::to_string(c.nodes_.size() - reached_count) +
             " BVH nodes are not reached from the root");
}

int MapCodec::check_plane_tree(const PlaneTree& tree, const StaticCollider& c) {
    const std::size_t slots = tree.ids_.size();
    for (std::size_t s = 0; s < slots; ++s)
        if (!c.has_triangle(tree.ids_[s]))
            fail(at("plane-tree slot", s) + "id " + std::to_string(tree.ids_[s]) +
                 " is not a triangle the collider keeps");
    const auto& nodes = tree.nodes_;
    const auto slab_nodes = std::count_if(nodes.begin(), nodes.end(),
                                          [](const PlaneTreeNode& n) { return n.has_slab(); });
    if (tree.slabs_.size() != std::size_t(slab_nodes))
        fail(std::to_string(tree.slabs_.size()) + " plane-tree slabs for " +
             std::to_string(slab_nodes) + " nodes with a slab");
    if (nodes.empty()) {
        if (slots != 0) fail("a plane tree without nodes over " + std::to_string(slots) + " slots");
        return 0;
    }
    // Depth first, left child first: the leaves must cover the slots in order, each once.
    struct Entry {
        std::uint32_t node;
        int depth;
    };
    std::vector<char> reached(nodes.size(), 0);
    std::vector<Entry> stack{{0, 0}};
    reached[0] = 1;
    std::size_t reached_count = 1;
    std::uint64_t next_slot = 0;
    int deepest = 0;
    while (!stack.empty()) {
        const Entry e = stack.back();
        stack.pop_back();
        const PlaneTreeNode& n = nodes[e.node];
        const auto where = [&] { return at("plane-tree node", e.node); };
        if (e.depth > PlaneTreeSettings::kMaxDepth)
            fail(where() + "deeper than " + std::to_string(PlaneTreeSettings::kMaxDepth));
        if (n.is_leaf()) {
            if (n.first != next_slot)
                fail(where() + "leaf starts at slot " + std::to_string(n.first) + ", not " +
                     std::to_string(next_slot));
            next_slot += n.count();
            if (next_slot > slots)
                fail(where() + "leaf ends past the " + std::to_string(slots) + " slots");
            deepest = std::max(deepest, e.depth);
            continue;
        }
        if (n.first >= nodes.size() || nodes.size() - n.first < 2)
            fail(where() + "children " + std::to_string(n.first) + " out of range (" +
                 std::to_string(nodes.size()) + " nodes)");
        for (const std::uint32_t child : {n.first, n.first + 1}) {
            if (reached[child]) fail(where() + "child " + std::to_string(child) + " reached twice");
            reached[child] = 1;
            ++reached_count;
        }
        if (std::uint64_t{nodes[n.first].count()} + nodes[n.first + 1].count() != n.count())
            fail(where() + "counts " + std::to_string(n.count()) + " triangles, its children " +
                 std::to_string(nodes[n.first].count() + nodes[n.first + 1].count()));
        stack.push_back({n.first + 1, e.depth + 1});
        stack.push_back({n.first, e.depth + 1});
    }
    if (next_slot != slots)
        fail("the plane tree's leaves cover " + std::to_string(next_slot) + " of " +
             std::to_string(slots) + " slots");
    if (reached_count != nodes.size())
        fail(std::to_string(nodes.size() - reached_count) +
             " plane-tree nodes are not reached from the root");
    return deepest;
}

}  // namespace trackphys::detail
