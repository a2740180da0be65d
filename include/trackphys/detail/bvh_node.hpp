#pragma once

#include <cstdint>

namespace trackphys {

/// One node of a StaticCollider's eight-wide bounding volume hierarchy: up to eight
/// children, their boxes stored lane by lane (structure of arrays) so that a query tests
/// them four at a time with a few SIMD comparisons (eight-wide rather than four: a car box
/// descends about 11 nodes instead of 15, each a dependent load). All nodes live in one
/// vector, root at 0, no parent links.
///
/// Bounds are float, rounded outward from the triangles' exact double bounds (never
/// inward), so a child box always holds every triangle of its subtree exactly: a query that
/// would hit a triangle always reaches it, and float halves the node size.
///
/// Every child covers a contiguous range of the collider's leaf-ordered triangles, the
/// lanes in order: lane i covers slots [first[i], first[i + 1]), the last used lane up to the
/// node's own end (its parent's bound for it, the triangle count at the root). A query can
/// report a whole child that lies inside its box without visiting it.
///
/// A lane is a leaf (its triangles are tested directly), an inner child (`child` is its node
/// index), or empty: NaN bounds, which fail every comparison, so that no query box, however
/// large or infinite, ever hits it; an empty lane's range is empty (first = the node's end).
struct alignas(64) BvhNode {
    static constexpr int kWidth = 8;
    /// `child` of a leaf (or empty) lane: no node below.
    static constexpr std::uint32_t kLeaf = 0x8000'0000u;

    float min[3][kWidth];         ///< 96 bytes: min[axis][lane] (m), rounded down
    float max[3][kWidth];         ///< 96 bytes: max[axis][lane] (m), rounded up
    std::uint32_t child[kWidth];  ///< 32 bytes: inner lane: child node index; else kLeaf
    std::uint32_t first[kWidth];  ///< 32 bytes: first triangle slot of each lane's range

    bool is_leaf(int lane) const { return (child[lane] & kLeaf) != 0; }
    /// True for an unused lane (NaN bounds).
    bool is_empty(int lane) const { return !(min[0][lane] <= max[0][lane]); }
    /// One past the last slot of lane `lane`'s range, given this node's own end.
    std::uint32_t end(int lane, std::uint32_t node_end) const {
        return lane + 1 < kWidth ? first[lane + 1] : node_end;
    }
};
// Aligned to a cache line (std::vector honours over-alignment since C++17): a node is
// exactly four lines, and its lanes load with aligned SIMD loads.
static_assert(sizeof(BvhNode) == 256, "BvhNode is 256 bytes: exactly four cache lines");

/// The grids in which BvhNode leaf lanes store their triangles' boxes in 16 bits
/// (src/collision/quantized_boxes.hpp): per axis, coordinate = (base + index) / inv_step.
/// Shared by the nodes of a subtree (StaticCollider: up to a few thousand triangles), or
/// one node's own. 48 bytes.
struct BvhNodeGrid {
    double inv_step[3];  ///< 1 / grid step (a power of two) per axis (1/m)
    double base[3];      ///< grid index of stored index 0 per axis (an integer)
};
static_assert(sizeof(BvhNodeGrid) == 48);

/// Eight consecutive leaf slots of a StaticCollider (from a multiple of 8): their triangles'
/// boxes in 16 bits (src/collision/quantized_boxes.hpp, QuantizedBlock's layout) and their
/// mesh triangle indices side by side, so that a query reads the indices it reports from the
/// two cache lines it has just tested (a separate index array costs a miss per block on cold
/// caches). Lanes past the last slot hold zeros (never read as a slot). 128 bytes.
struct alignas(64) BvhSlotBlock {
    static constexpr int kLanes = 8;
    std::int16_t box[6][kLanes];     ///< 96 bytes: min x, y, z, max x, y, z, biased indices
    std::uint32_t triangle[kLanes];  ///< 32 bytes: the mesh index of each slot's triangle
};
static_assert(sizeof(BvhSlotBlock) == 128, "BvhSlotBlock is 128 bytes: two cache lines");

}  // namespace trackphys
