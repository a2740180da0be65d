#pragma once

#include <algorithm>
#include <charconv>
#include <cstdint>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "io/mesh_checks.hpp"
#include "trackphys/error.hpp"

namespace trackphys::detail {

/// Lines and words of a text mesh format, read strictly: a line ends at "\n" (a "\r" before
/// it is dropped), words are split at blanks (space, tab), and any other control character
/// is refused, since assimp's readers each cut lines and words at their own set of them and
/// a file they would read differently from this scanner must not pass. Failures name the
/// line (MeshCheckError).
class TextScanner {
  public:
    /// lines_before: how many lines of the file precede text (line numbers count from there).
    explicit TextScanner(std::string_view text, std::size_t lines_before = 0)
        : text_(text), line_(lines_before) {}

    bool at_end() const { return at_ >= text_.size(); }
    std::size_t line_number() const { return line_; }
    /// Where the next line starts, in bytes from the start of the text.
    std::size_t offset() const { return at_; }

    /// The next line's words (none for a blank line). Precondition: !at_end().
    const std::vector<std::string_view>& next_line() {
        ++line_;
        const std::size_t end = std::min(text_.find('\n', at_), text_.size());
        std::string_view line = text_.substr(at_, end - at_);
        at_ = end < text_.size() ? end + 1 : end;
        if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
        words_.clear();
        for (std::size_t i = 0; i < line.size();) {
            if (is_blank(line[i])) {
                ++i;
                continue;
            }
            const std::size_t start = i;
            while (i < line.size() && !is_blank(line[i])) {
                const auto byte = static_cast<unsigned char>(line[i]);
                if (byte < 0x20 || byte == 0x7f)
                    fail("control character " + std::to_string(byte) + " in the text");
                ++i;
            }
            words_.push_back(line.substr(start, i - start));
        }
        return words_;
    }

    /// Skips bytes of free data (an AC3D object's `data`), counting its lines; false when the
    /// text ends first.
    bool skip_bytes(std::uint64_t bytes) {
        if (bytes > text_.size() - at_) return false;
        const std::string_view skipped = text_.substr(at_, static_cast<std::size_t>(bytes));
        line_ += static_cast<std::size_t>(std::count(skipped.begin(), skipped.end(), '\n'));
        at_ += static_cast<std::size_t>(bytes);
        return true;
    }

    /// The words of the line read last.
    const std::vector<std::string_view>& words() const { return words_; }

    /// The next line that holds a word, skipping blank lines and those whose first word
    /// starts with comment_start (when given). Empty at the end of the text.
    const std::vector<std::string_view>& next_content_line(char comment_start = '\0') {
        while (!at_end()) {
            next_line();
            if (!words_.empty() && (comment_start == '\0' || words_[0][0] != comment_start))
                return words_;
        }
        words_.clear();
        return words_;
    }

    /// A count: decimal digits only, at most max (2^32 - 1 unless told).
    std::uint64_t count(std::string_view word, std::string_view what,
                        std::uint64_t max = std::numeric_limits<std::uint32_t>::max()) const {
        std::uint64_t value = 0;
        const auto [end, error] = std::from_chars(word.data(), word.data() + word.size(), value);
        if (word.empty() || word[0] == '+' || error != std::errc() ||
            end != word.data() + word.size() || value > max)
            fail(std::string(what) + " " + quoted_text(word) + " is not a count from 0 to " +
                 std::to_string(max));
        return value;
    }

    /// A signed decimal integer (an index that may count from the end).
    std::int64_t integer(std::string_view word, std::string_view what) const {
        std::int64_t value = 0;
        const auto [end, error] = std::from_chars(word.data(), word.data() + word.size(), value);
        if (word.empty() || error != std::errc() || end != word.data() + word.size())
            fail(std::string(what) + " " + quoted_text(word) + " is not an integer");
        return value;
    }

    /// A real number, the whole word (a leading '+' allowed; nan and inf pass, for load_mesh
    /// to report against the vertex).
    double real(std::string_view word, std::string_view what) const {
        std::string_view digits = word;
        if (!digits.empty() && digits[0] == '+') digits.remove_prefix(1);
        double value = 0;
        const auto [end, error] =
            std::from_chars(digits.data(), digits.data() + digits.size(), value);
        if (digits.empty() || (error != std::errc() && error != std::errc::result_out_of_range) ||
            end != digits.data() + digits.size())
            fail(std::string(what) + " " + quoted_text(word) + " is not a number");
        return value;
    }

    /// Fails unless the current line has between min and max words.
    void expect_words(std::size_t min, std::size_t max, std::string_view what) const {
        if (words_.size() < min || words_.size() > max)
            fail(std::string(what) + " has " + std::to_string(words_.size()) + " words, expected " +
                 (min == max ? std::to_string(min)
                             : std::to_string(min) + " to " + std::to_string(max)));
    }

    [[noreturn]] void fail(const std::string& reason) const {
        throw MeshCheckError{"line " + std::to_string(line_) + ": " + reason};
    }

  private:
    static bool is_blank(char ch) { return ch == ' ' || ch == '\t'; }

    std::string_view text_;
    std::size_t at_ = 0;
    std::size_t line_ = 0;
    std::vector<std::string_view> words_;
};

}  // namespace trackphys::detail
