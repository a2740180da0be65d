#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "trackphys/export.hpp"
#include "trackphys/geometry/normalized_triangle.hpp"

namespace trackphys {

class PlaneTree;

/// The frames that queries of collider plane trees build (a collider's tree keeps none),
/// kept so that later queries reuse them instead of building them again (a car's queries
/// meet the same few road triangles step after step), at addresses that stay put until
/// clear(): MidPhase candidates point at them. No allocation once the storage has grown to
/// the most frames held between two clear() calls.
class TRACKPHYS_API PlaneTreeFrameCache {
  public:
    /// The frame of `tree`'s slot `slot` (PlaneTree::triangle), built on the first call
    /// since the last clear(). `tree` must stay alive and unchanged until then.
    const NormalizedTriangle& frame(const PlaneTree& tree, std::uint32_t slot);
    /// Forgets every frame (their storage is reused).
    void clear();
    /// Bytes of storage held.
    std::size_t bytes_used() const;

  private:
    struct Entry {
        const PlaneTree* tree = nullptr;
        std::uint32_t slot = 0;
        std::uint32_t stamp = 0;  ///< free unless it is stamp_
        const NormalizedTriangle* frame = nullptr;
    };
    static constexpr std::size_t kBlock = 64;  ///< frames in the first block

    const NormalizedTriangle* keep(const NormalizedTriangle& frame);
    void grow_index();

    // Frames in blocks that never reallocate (moving a block's vector moves no frame); the
    // blocks before filling_ are full, those after it empty.
    std::vector<std::vector<NormalizedTriangle>> blocks_;
    std::size_t filling_ = 0;
    // Frames by (tree, slot): open addressing, a power-of-two size at least twice the
    // entries.
    std::vector<Entry> index_;
    std::size_t entries_ = 0;
    std::uint32_t stamp_ = 1;
};

}  // namespace trackphys
