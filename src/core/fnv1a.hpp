#pragma once

// FNV-1a 64 (Fowler, Noll, Vo): the library's one hash for state hashes, fingerprints and
// file checksums. Not cryptographic: it tells apart states, worlds and files that differ by
// accident (a bit flip, another mesh), which is all trackphys asks of it.

#include <bit>
#include <cstddef>
#include <cstdint>

#include <glm/gtc/quaternion.hpp>
#include <glm/vec3.hpp>

namespace trackphys::core {

/// FNV-1a over raw bytes: the hash sees every bit of every value it is given.
struct Fnv1a {
    static constexpr std::uint64_t kOffset = 0xcbf29ce484222325ull;
    static constexpr std::uint64_t kPrime = 0x100000001b3ull;

    std::uint64_t value = kOffset;

    void add(const void* data, std::size_t size) {
        const auto* bytes = static_cast<const unsigned char*>(data);
        for (std::size_t i = 0; i < size; ++i) value = (value ^ bytes[i]) * kPrime;
    }
    void add(double x) { add(&x, sizeof x); }
    void add(std::uint64_t x) { add(&x, sizeof x); }
    void add(const glm::dvec3& v) { add(v.x), add(v.y), add(v.z); }
    void add(const glm::dquat& q) { add(q.w), add(q.x), add(q.y), add(q.z); }
};

/// The same idea a 64-bit word at a time, for bulk data (a whole track mesh, where byte by
/// byte would be several times slower): multiply after each xor, then fold the high half
/// down so that every bit of a word reaches every bit of the result. Each step is a
/// bijection of the running value, so two inputs that differ in one word always hash
/// differently.
struct WordHash {
    std::uint64_t value = Fnv1a::kOffset;

    void add(std::uint64_t word) {
        value = (value ^ word) * Fnv1a::kPrime;
        value ^= value >> 32;
    }
    void add(double x) { add(std::bit_cast<std::uint64_t>(x)); }
    void add(const glm::dvec3& v) { add(v.x), add(v.y), add(v.z); }
};

}  // namespace trackphys::core
