#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "trackphys/export.hpp"
#include "trackphys/geometry/normalized_triangle.hpp"

namespace trackphys {

class PlaneTree;

/// The frames that queries of collider plane trees build (the trees that keep none,
/// PlaneTreeFrames::built), kept so that later queries reuse them instead of building them again (a
/// car's queries meet the same few road triangles step after step), at addresses that stay put
/// until clear(): MidPhase candidates point at them. For a tree that keeps its frames, reported()
/// points into the tree, whose frames live as long as it does. Frames are kept by leaf run (up to
/// 64 slots of one leaf, side by side in slot order), so that a query finds a leaf's frames with
/// one lookup. No allocation once the storage has grown to the most room that runs take between two
/// clear() calls.
class TRACKPHYS_API PlaneTreeFrameCache {
  public:
    /// The largest run: a leaf of more slots is kept as several runs.
    static constexpr std::uint32_t kMaxRun = 64;

    /// Storage for the frames of `tree`'s slots first .. first + count - 1 (count in
    /// [1, kMaxRun], all of one leaf), of which those in `needed` (bit k: slot first + k) are
    /// built by now (PlaneTree::triangle); read no slot not asked for yet. Until clear(), a
    /// run is asked for with the count it was first asked for (checked by TP_ASSERT), and
    /// `tree` stays alive and unchanged.
    const NormalizedTriangle* run(const PlaneTree& tree, std::uint32_t first, std::uint32_t count,
                                  std::uint64_t needed);
    /// The frames of the slots the last query given this cache reported, in its order.
    std::span<const NormalizedTriangle* const> reported() const { return reported_; }
    /// Forgets every frame (their storage is reused).
    void clear();
    /// Bytes of storage held.
    std::size_t bytes_used() const;

  private:
    friend class PlaneTree;  // fills reported_

    struct Entry {
        const PlaneTree* tree = nullptr;
        std::uint32_t first = 0;
        std::uint32_t stamp = 0;  ///< free unless it is stamp_
        std::uint32_t count = 0;  ///< the run's slots, room reserved at frames
        std::uint64_t built = 0;  ///< bit k: frames[k] is slot first + k's
        NormalizedTriangle* frames = nullptr;
    };
    // Frames in the first block: a run takes room for each slot of its leaf, built or
    // not, so the first block is large enough for a car's update to stay within it after
    // its first updates (a race that allocates once warm fails WorldAllocation's test).
    static constexpr std::size_t kBlock = 1024;

    NormalizedTriangle* reserve(std::uint32_t count);
    void grow_index();

    // Room for frames, built in place only when asked for (a run's other slots stay raw
    // storage), in blocks that never move; the blocks before filling_ are full or hold no
    // room for the next run, those after it empty.
    struct Block {
        std::unique_ptr<std::byte[]> bytes;
        std::size_t capacity = 0;  ///< frames
        std::size_t used = 0;      ///< frames handed to runs
    };
    std::vector<Block> blocks_;
    std::size_t filling_ = 0;
    // Runs by (tree, first slot): open addressing, a power-of-two size at least twice the
    // entries.
    std::vector<Entry> index_;
    std::size_t entries_ = 0;
    std::uint32_t stamp_ = 1;
    std::vector<const NormalizedTriangle*> reported_;
};

}  // namespace trackphys
