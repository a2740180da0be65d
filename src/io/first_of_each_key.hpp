#pragma once

#include <algorithm>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace trackphys::detail {

/// Tells, for an element appended to a list, the first element of the list with the same
/// key: the question a mesh file's assembly asks of every corner (is this position welded to
/// a vertex already there?) and of every triangle (does it repeat one kept before?).
///
/// An open-addressing table of 32-bit indices into the caller's list, each beside a tag of
/// its key's hash, so that a probe reads the list only when the tags agree; at most half
/// full: 16 to 32 bytes an element remembered, no allocation each (as std::unordered_map's
/// nodes took).
///
/// KeyOf gives `Key operator()(const Element&) const` (keys compare with ==) and
/// `std::uint64_t hash(const Key&) const`, well mixed in every bit.
template <class Element, class KeyOf>
class FirstOfEachKey {
  public:
    explicit FirstOfEachKey(const std::vector<Element>& list, KeyOf key_of = {})
        : list_(list), key_of_(std::move(key_of)) {}

    /// The index of the first element remembered whose key is list[index]'s, or index
    /// itself, which is then remembered, when there is none. index < 2^32 - 1. The list may
    /// grow between calls; the elements remembered must not change.
    std::size_t first_of(std::size_t index) {
        if (2 * (remembered_ + 1) > slots_.size())
            rehash(std::max<std::size_t>(16, 2 * slots_.size()));
        const auto key = key_of_(list_[index]);
        const std::uint64_t hash = key_of_.hash(key);
        Slot& slot = slots_[slot_of(key, hash)];
        if (slot.index != kEmpty) return slot.index;
        slot = {static_cast<std::uint32_t>(index), static_cast<std::uint32_t>(hash >> 32)};
        ++remembered_;
        return index;
    }

    /// Makes room for this many elements remembered, so that the table is not rebuilt on
    /// the way there (a rebuild reads every element remembered).
    void reserve(std::size_t elements) {
        if (2 * elements > slots_.size()) rehash(std::bit_ceil(2 * elements));
    }

  private:
    struct Slot {
        std::uint32_t index;  ///< into the list; kEmpty where free
        std::uint32_t tag;    ///< the high half of the key's hash
    };
    static constexpr std::uint32_t kEmpty = 0xFFFFFFFFu;

    // The slot holding key, or the free slot where it would go: linear probing from the
    // hash's low bits.
    template <class Key>
    std::size_t slot_of(const Key& key, std::uint64_t hash) const {
        const std::size_t mask = slots_.size() - 1;
        const auto tag = static_cast<std::uint32_t>(hash >> 32);
        for (std::size_t slot = hash & mask;; slot = (slot + 1) & mask) {
            const Slot& s = slots_[slot];
            if (s.index == kEmpty || (s.tag == tag && key_of_(list_[s.index]) == key)) return slot;
        }
    }

    void rehash(std::size_t size) {
        const std::vector<Slot> old = std::exchange(slots_, std::vector<Slot>(size, {kEmpty, 0}));
        for (const Slot& s : old) {
            if (s.index == kEmpty) continue;
            const auto key = key_of_(list_[s.index]);
            slots_[slot_of(key, key_of_.hash(key))] = s;
        }
    }

    const std::vector<Element>& list_;
    KeyOf key_of_;
    std::vector<Slot> slots_;  // a power of two of them
    std::size_t remembered_ = 0;
};

}  // namespace trackphys::detail
