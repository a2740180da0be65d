#pragma once

// The pieces of a map file (private; layout in docs/tpmap.md): records and arrays of
// trivially copyable types, stored as their bytes (the format is little-endian; the codec
// refuses other hosts), each padded with zeros to a multiple of kMapAlignment so that every
// array starts aligned as in memory and the checksum reads whole words.

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <deque>
#include <limits>
#include <ostream>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "trackphys/error.hpp"

namespace trackphys::map_detail {

inline constexpr std::size_t kMapAlignment = 64;

inline std::size_t padded(std::size_t bytes) {
    return (bytes + kMapAlignment - 1) / kMapAlignment * kMapAlignment;
}

/// The map checksum: four interleaved word hashes (core::WordHash's step: xor, multiply by
/// the FNV prime, fold the high half), folded together at the end. Four chains instead of
/// one keep the multiplier busy: the checksum of a large map costs a fraction of reading
/// it. Each step is a bijection of its chain's value, so a file that differs from another
/// in one word always has another checksum.
class MapChecksum {
  public:
    /// Adds `bytes` (a multiple of 8) as little-endian words, continuing the word count.
    void add(const void* data, std::size_t bytes);
    std::uint64_t value() const;

  private:
    std::uint64_t lanes_[4] = {0xcbf29ce484222325ull, 0x84222325cbf29ce4ull, 0x9ce484222325cbf2ull,
                               0x2325cbf29ce48422ull};
    std::uint64_t words_ = 0;
};

/// Gathers a map body as pieces that point at the caller's arrays (no copy), with records
/// copied into storage of its own.
class BodyWriter {
  public:
    template <class T>
    void record(const T& value) {
        static_assert(std::is_trivially_copyable_v<T>);
        std::string& bytes = owned_.emplace_back(padded(sizeof(T)), '\0');
        std::memcpy(bytes.data(), &value, sizeof(T));
        pieces_.push_back({bytes.data(), sizeof(T)});
    }
    template <class T>
    void array(const std::vector<T>& values) {
        static_assert(std::is_trivially_copyable_v<T>);
        pieces_.push_back(
            {reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T)});
    }

    /// Body bytes, padding included.
    std::uint64_t size() const;
    /// Adds the body, padding included, to the checksum.
    void add_to(MapChecksum& checksum) const;
    /// Writes the body, padding included.
    void write_to(std::ostream& out) const;

  private:
    struct Piece {
        const char* data;
        std::size_t size;
    };
    std::deque<std::string> owned_;  // a deque: growing it never moves a record
    std::vector<Piece> pieces_;
};

/// Where an array lies in a body that BodyReader checked, to be copied out later (the
/// loader copies the colliders' arrays on several threads).
template <class T>
struct ArrayBytes {
    const char* from = nullptr;
    std::size_t count = 0;

    void copy_to(std::vector<T>& out) const {
        out.resize(count);
        if (count != 0) std::memcpy(out.data(), from, count * sizeof(T));
    }
};

/// Reads a map body back, every read checked against the bytes left. Messages name what was
/// read; the codec adds the file and the collider.
class BodyReader {
  public:
    explicit BodyReader(std::string_view body) : body_(body) {}

    template <class T>
    T record(const char* what) {
        static_assert(std::is_trivially_copyable_v<T>);
        T value;
        std::memcpy(&value, take(sizeof(T), 1, what), sizeof(T));
        return value;
    }
    /// The place of `count` elements, checked against the bytes left (nothing is copied).
    template <class T>
    ArrayBytes<T> array(std::uint64_t count, const char* what) {
        static_assert(std::is_trivially_copyable_v<T>);
        return {take(sizeof(T), count, what), static_cast<std::size_t>(count)};
    }
    /// `count` elements into `out` (resized), checked against the bytes left before any
    /// allocation.
    template <class T>
    void array(std::vector<T>& out, std::uint64_t count, const char* what) {
        array<T>(count, what).copy_to(out);
    }
    std::size_t left() const { return body_.size() - at_; }

  private:
    const char* take(std::size_t element, std::uint64_t count, const char* what);

    std::string_view body_;
    std::size_t at_ = 0;
};

}  // namespace trackphys::map_detail
