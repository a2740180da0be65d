#pragma once

#include <cstddef>
#include <cstdint>
#include <new>

namespace trackphys {

/// One node of a StaticCollider's bounding volume hierarchy (the madmann91/bvh layout:
/// all nodes in one vector, root at 0, the two children of an inner node adjacent at
/// `first` and `first + 1`, no parent links).
///
/// Bounds are float, rounded outward from the triangles' exact double bounds (never
/// inward), so a node box always holds every triangle of its subtree exactly: a query that
/// would hit a triangle always reaches it, and float halves the node size.
///
/// Every subtree covers a contiguous range of the collider's leaf-ordered triangles, so a
/// node also keeps its subtree's triangle count: traversal carries the range's first slot
/// and can report a whole subtree that lies inside a query box without visiting it.
struct BvhNode {
    static constexpr std::uint32_t kLeafBit = 0x8000'0000u;

    float min[3];          ///< 12 bytes: box minimum (m), rounded down
    float max[3];          ///< 12 bytes: box maximum (m), rounded up
    std::uint32_t first;   ///<  4 bytes: leaf: first triangle slot; inner: left child index
    std::uint32_t packed;  ///<  4 bytes: kLeafBit for a leaf | triangles in the subtree

    bool is_leaf() const { return (packed & kLeafBit) != 0; }
    /// Number of triangles in this node's subtree (a leaf's own triangles).
    std::uint32_t count() const { return packed & ~kLeafBit; }
};
static_assert(sizeof(BvhNode) == 32, "BvhNode is 32 bytes: two siblings share a cache line");

/// Allocates on 64-byte boundaries, so that with the root at 0 and an unused node at 1 every
/// sibling pair (2k, 2k + 1) fills exactly one cache line.
template <class T>
struct CacheLineAllocator {
    using value_type = T;
    static constexpr std::align_val_t kAlignment{64};

    CacheLineAllocator() = default;
    template <class U>
    CacheLineAllocator(const CacheLineAllocator<U>&) noexcept {}

    T* allocate(std::size_t n) {
        return static_cast<T*>(::operator new(n * sizeof(T), kAlignment));
    }
    void deallocate(T* p, std::size_t) noexcept { ::operator delete(p, kAlignment); }

    template <class U>
    bool operator==(const CacheLineAllocator<U>&) const noexcept {
        return true;
    }
};

}  // namespace trackphys
