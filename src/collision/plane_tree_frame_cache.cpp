#include "trackphys/collision/plane_tree_frame_cache.hpp"

#include <cstdint>

#include "trackphys/collision/plane_tree.hpp"

namespace trackphys {
namespace {

std::size_t hash(const PlaneTree* tree, std::uint32_t slot) {
    const auto bits = reinterpret_cast<std::uintptr_t>(tree);
    return static_cast<std::size_t>(
        (bits ^ (std::uint64_t{slot} * 0x9e3779b97f4a7c15ull)) * 0xff51afd7ed558ccdull >> 17);
}

}  // namespace

const NormalizedTriangle& PlaneTreeFrameCache::frame(const PlaneTree& tree, std::uint32_t slot) {
    if (2 * (entries_ + 1) > index_.size()) grow_index();
    const std::size_t mask = index_.size() - 1;
    for (std::size_t at = hash(&tree, slot) & mask;; at = (at + 1) & mask) {
        Entry& e = index_[at];
        if (e.stamp != stamp_) {
            e = {&tree, slot, stamp_, keep(tree.triangle(slot))};
            ++entries_;
            return *e.frame;
        }
        if (e.tree == &tree && e.slot == slot) return *e.frame;
    }
}

void PlaneTreeFrameCache::clear() {
    // A new stamp frees every entry at once; only its wrap-around visits them.
    if (++stamp_ == 0) {
        for (Entry& e : index_) e.stamp = 0;
        stamp_ = 1;
    }
    entries_ = 0;
    for (std::size_t b = 0; b < blocks_.size() && b <= filling_; ++b) blocks_[b].clear();
    filling_ = 0;
}

const NormalizedTriangle* PlaneTreeFrameCache::keep(const NormalizedTriangle& frame) {
    // Each block twice the one before: storage doubles when it grows, so that a new peak
    // allocates once, and rarely after a World's first updates.
    if (filling_ == blocks_.size()) blocks_.emplace_back().reserve(kBlock << blocks_.size());
    std::vector<NormalizedTriangle>& block = blocks_[filling_];
    block.push_back(frame);  // within its capacity: the frames already handed out stay put
    if (block.size() == block.capacity()) ++filling_;
    return &block.back();
}

void PlaneTreeFrameCache::grow_index() {
    // Room for a few thousand frames from the start: a car's frames between two clear()
    // calls reach a thousand and more, and growing mid-race would allocate.
    std::vector<Entry> old(index_.size() < 4096 ? 4096 : 2 * index_.size());
    old.swap(index_);
    const std::size_t mask = index_.size() - 1;
    for (const Entry& e : old) {
        if (e.stamp != stamp_) continue;
        std::size_t at = hash(e.tree, e.slot) & mask;
        while (index_[at].stamp == stamp_) at = (at + 1) & mask;
        index_[at] = e;
    }
}

std::size_t PlaneTreeFrameCache::bytes_used() const {
    std::size_t frames = 0;
    for (const std::vector<NormalizedTriangle>& block : blocks_) frames += block.capacity();
    return frames * sizeof(NormalizedTriangle) + index_.capacity() * sizeof(Entry);
}

}  // namespace trackphys
