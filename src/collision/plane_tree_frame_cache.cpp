#include "trackphys/collision/plane_tree_frame_cache.hpp"

#include <bit>
#include <cstdint>
#include <memory>
#include <type_traits>

#include "trackphys/assert.hpp"
#include "trackphys/collision/plane_tree.hpp"

namespace trackphys {
namespace {

std::size_t hash(const PlaneTree* tree, std::uint32_t first) {
    const auto bits = reinterpret_cast<std::uintptr_t>(tree);
    return static_cast<std::size_t>(
        (bits ^ (std::uint64_t{first} * 0x9e3779b97f4a7c15ull)) * 0xff51afd7ed558ccdull >> 17);
}

// Frames are built in raw storage and never destroyed: reusing it is all clear() does.
static_assert(std::is_trivially_destructible_v<NormalizedTriangle>);

}  // namespace

const NormalizedTriangle* PlaneTreeFrameCache::run(const PlaneTree& tree, std::uint32_t first,
                                                   std::uint32_t count, std::uint64_t needed) {
    TP_ASSERT(count >= 1 && count <= kMaxRun && (count == kMaxRun || needed >> count == 0),
              "plane tree frame cache: bad run");
    if (2 * (entries_ + 1) > index_.size()) grow_index();
    const std::size_t mask = index_.size() - 1;
    std::size_t at = hash(&tree, first) & mask;
    while (index_[at].stamp == stamp_ && !(index_[at].tree == &tree && index_[at].first == first))
        at = (at + 1) & mask;
    Entry& e = index_[at];
    if (e.stamp != stamp_) {
        e = {&tree, first, stamp_, count, 0, reserve(count)};
        ++entries_;
    }
    TP_ASSERT(e.count == count, "plane tree frame cache: a run asked for with another count");
    for (std::uint64_t missing = needed & ~e.built; missing != 0; missing &= missing - 1) {
        const int k = std::countr_zero(missing);
        std::construct_at(e.frames + k, tree.triangle(first + static_cast<std::uint32_t>(k)));
    }
    e.built |= needed;
    return e.frames;
}

void PlaneTreeFrameCache::clear() {
    // A new stamp frees every entry at once; only its wrap-around visits them.
    if (++stamp_ == 0) {
        for (Entry& e : index_) e.stamp = 0;
        stamp_ = 1;
    }
    entries_ = 0;
    for (std::size_t b = 0; b < blocks_.size() && b <= filling_; ++b) blocks_[b].used = 0;
    filling_ = 0;
    reported_.clear();
}

NormalizedTriangle* PlaneTreeFrameCache::reserve(std::uint32_t count) {
    // Each block twice the one before (the first holds runs of kMaxRun): storage doubles
    // when it grows, so that a new peak allocates once, and rarely after a World's first
    // updates.
    for (;; ++filling_) {
        if (filling_ == blocks_.size()) {
            const std::size_t capacity = kBlock << blocks_.size();
            blocks_.push_back({std::make_unique<std::byte[]>(capacity * sizeof(NormalizedTriangle)),
                               capacity, 0});
        }
        Block& block = blocks_[filling_];
        if (block.capacity - block.used < count) continue;
        auto* frames = reinterpret_cast<NormalizedTriangle*>(block.bytes.get()) + block.used;
        block.used += count;
        return frames;
    }
}

void PlaneTreeFrameCache::grow_index() {
    // Room for thousands of runs from the start, more than a car's update meets between two
    // clear() calls: growing mid-race would allocate.
    std::vector<Entry> old(index_.size() < 4096 ? 4096 : 2 * index_.size());
    old.swap(index_);
    const std::size_t mask = index_.size() - 1;
    for (const Entry& e : old) {
        if (e.stamp != stamp_) continue;
        std::size_t at = hash(e.tree, e.first) & mask;
        while (index_[at].stamp == stamp_) at = (at + 1) & mask;
        index_[at] = e;
    }
}

std::size_t PlaneTreeFrameCache::bytes_used() const {
    std::size_t frames = 0;
    for (const Block& block : blocks_) frames += block.capacity;
    return frames * sizeof(NormalizedTriangle) + index_.capacity() * sizeof(Entry) +
           reported_.capacity() * sizeof(const NormalizedTriangle*);
}

}  // namespace trackphys
