#include "map_body.hpp"

#include <array>

namespace trackphys::map_detail {
namespace {

constexpr std::uint64_t kPrime = 0x100000001b3ull;

std::uint64_t step(std::uint64_t value, std::uint64_t word) {
    value = (value ^ word) * kPrime;
    return value ^ (value >> 32);
}

const std::array<char, kMapAlignment> kZeros{};

}  // namespace

void MapChecksum::add(const void* data, std::size_t bytes) {
    const auto* from = static_cast<const char*>(data);
    const std::size_t words = bytes / 8;
    const auto word = [&](std::size_t k) {
        std::uint64_t w;
        std::memcpy(&w, from + 8 * k, 8);
        return w;
    };
    std::size_t i = 0;
    const auto one_word = [&] {
        std::uint64_t& lane = lanes_[words_++ % 4];
        lane = step(lane, word(i++));
    };
    while (i < words && words_ % 4 != 0) one_word();
    // Four words at a time, the lanes in registers so that their four chains run side by
    // side: the same steps in the same order per lane.
    std::uint64_t a = lanes_[0], b = lanes_[1], c = lanes_[2], d = lanes_[3];
    const std::size_t first = i, whole = i + (words - i) / 4 * 4;
    for (; i < whole; i += 4) {
        a = step(a, word(i));
        b = step(b, word(i + 1));
        c = step(c, word(i + 2));
        d = step(d, word(i + 3));
    }
    lanes_[0] = a;
    lanes_[1] = b;
    lanes_[2] = c;
    lanes_[3] = d;
    words_ += whole - first;
    while (i < words) one_word();
}

std::uint64_t MapChecksum::value() const {
    std::uint64_t value = step(lanes_[0], words_);
    for (int i = 1; i < 4; ++i) value = step(value, lanes_[i]);
    return value;
}

std::uint64_t BodyWriter::size() const {
    std::uint64_t total = 0;
    for (const Piece& p : pieces_) total += padded(p.size);
    return total;
}

void BodyWriter::add_to(MapChecksum& checksum) const {
    for (const Piece& p : pieces_) {
        const std::size_t whole = p.size / 8 * 8;
        checksum.add(p.data, whole);
        // The last partial word and the padding, as they will be written.
        std::array<char, kMapAlignment> tail{};
        // An empty array's data may be null, which memcpy must not be given even for 0 bytes.
        if (p.size > whole) std::memcpy(tail.data(), p.data + whole, p.size - whole);
        checksum.add(tail.data(), padded(p.size) - whole);
    }
}

void BodyWriter::write_to(std::ostream& out) const {
    for (const Piece& p : pieces_) {
        out.write(p.data, static_cast<std::streamsize>(p.size));
        out.write(kZeros.data(), static_cast<std::streamsize>(padded(p.size) - p.size));
    }
}

const char* BodyReader::take(std::size_t element, std::uint64_t count, const char* what) {
    const std::size_t room = left();
    if (count > room / element)
        throw Error(std::string("the body is truncated: ") + what + " needs " +
                    std::to_string(count) + " x " + std::to_string(element) + " bytes, " +
                    std::to_string(room) + " left");
    const char* from = body_.data() + at_;
    const std::size_t bytes = static_cast<std::size_t>(count) * element;
    at_ += std::min(padded(bytes), room);
    return from;
}

}  // namespace trackphys::map_detail
