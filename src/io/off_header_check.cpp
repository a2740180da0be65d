#include "io/off_header_check.hpp"

#include <string>

namespace trackphys::detail {
namespace {

// The header as assimp's OFF reader walks it: a cursor over the file's first bytes.
class HeaderCursor {
  public:
    explicit HeaderCursor(std::string text) : text_(std::move(text)) {}

    // Blanks and line ends, then whole lines that start with '#' (comments) or are empty.
    void next_token() {
        skip_spaces_and_line_ends();
        while (at_ < text_.size() && (text_[at_] == '#' || is_line_end(text_[at_]))) {
            while (at_ < text_.size() && !is_line_end(text_[at_])) ++at_;
            skip_spaces_and_line_ends();
        }
    }
    bool take(const char* word) {
        const std::string w(word);
        if (text_.compare(at_, w.size(), w) != 0 || at_ + w.size() >= text_.size()) return false;
        at_ += w.size();
        return true;
    }
    bool at_digit() const { return at_ < text_.size() && text_[at_] >= '0' && text_[at_] <= '9'; }
    // Decimal digits from here, as unsigned 32-bit arithmetic wraps them (strtoul10).
    std::uint32_t number() {
        std::uint32_t value = 0;
        for (; at_digit(); ++at_)
            value = value * 10u + static_cast<std::uint32_t>(text_[at_] - '0');
        return value;
    }

  private:
    static bool is_line_end(char ch) {
        return ch == '\n' || ch == '\r' || ch == '\0' || ch == '\f';
    }
    void skip_spaces_and_line_ends() {
        while (at_ < text_.size() &&
               (text_[at_] == ' ' || text_[at_] == '\t' || is_line_end(text_[at_])))
            ++at_;
    }

    std::string text_;
    std::size_t at_ = 0;
};

}  // namespace

std::optional<std::string> off_header_problem(std::istream& in, std::uintmax_t file_size,
                                              bool any_header) {
    std::string head(64 * 1024, '\0');
    in.read(head.data(), static_cast<std::streamsize>(head.size()));
    head.resize(static_cast<std::size_t>(in.gcount()));
    HeaderCursor cursor(std::move(head));
    cursor.next_token();
    // Optional prefixes, in this order: ST (texture coordinates), C, N, 4, n (dimension).
    cursor.take("ST");
    cursor.take("C");
    cursor.take("N");
    cursor.take("4");
    const bool has_dimension = cursor.take("n");
    if (cursor.take("OFF")) {
        cursor.next_token();
    } else {
        if (!any_header) return std::nullopt;
        cursor.next_token();
        if (!cursor.at_digit()) return std::nullopt;  // assimp: "Header is invalid"
    }
    if (has_dimension) {
        if (cursor.number() > 3) return std::nullopt;  // assimp refuses it
        cursor.next_token();
    }
    cursor.next_token();
    const std::uint32_t vertices = cursor.number();
    cursor.next_token();
    const std::uint32_t faces = cursor.number();
    if (vertices <= file_size && faces <= file_size) return std::nullopt;
    return "OFF header claims " + std::to_string(vertices) + " vertices and " +
           std::to_string(faces) + " faces, more than the file's " + std::to_string(file_size) +
           " bytes can hold";
}

}  // namespace trackphys::detail
