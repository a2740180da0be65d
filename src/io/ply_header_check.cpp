#include "io/ply_header_check.hpp"

#include <cctype>
#include <cstddef>
#include <iterator>
#include <vector>

namespace trackphys::detail {
namespace {

// assimp's PLY reader splits lines at these, and words at blanks only (a '\v' after
// "end_header" keeps it from matching: found by fuzz_mesh_import as another hang).
bool is_line_end(char ch) { return ch == '\n' || ch == '\r' || ch == '\0' || ch == '\f'; }
bool is_blank(char ch) { return ch == ' ' || ch == '\t'; }

// The words of a header line, split as assimp splits them.
std::vector<std::string> words_of(const std::string& line) {
    std::vector<std::string> words;
    for (std::size_t i = 0; i < line.size();) {
        while (i < line.size() && is_blank(line[i])) ++i;
        const std::size_t start = i;
        while (i < line.size() && !is_blank(line[i])) ++i;
        if (i > start) words.push_back(line.substr(start, i - start));
    }
    return words;
}

enum class Line { none, ended, last };  // nothing left; a line and its end; a line at EOF

// The next header line as assimp's stream reader cuts it, at most kKept characters of it
// (only its first words matter). The reader ends a line at any line-end character and
// consumes that one character; when the next line then starts at a line-end character, it
// skips everything through the next '\n'. So "a\0\0end_header\n" never shows end_header
// (found by fuzz_mesh_import as another hang).
constexpr std::size_t kKept = 256;
Line next_line(std::istreambuf_iterator<char>& it, std::string& line) {
    const std::istreambuf_iterator<char> end;
    line.clear();
    if (it != end && is_line_end(*it)) {
        while (it != end && *it != '\n') ++it;
        if (it != end) ++it;
    }
    if (it == end) return Line::none;
    for (; it != end; ++it) {
        const char ch = *it;
        if (is_line_end(ch)) {
            ++it;
            return Line::ended;
        }
        if (line.size() < kKept) line.push_back(ch);
    }
    return Line::last;
}

}  // namespace

std::optional<std::string> ply_header_problem(std::istream& in, std::uintmax_t file_size) {
    std::istreambuf_iterator<char> it(in);
    std::string line;
    if (next_line(it, line) == Line::none || line.size() < 3) return std::nullopt;
    for (std::size_t i = 0; i < 3; ++i)
        if (std::tolower(static_cast<unsigned char>(line[i])) != "ply"[i]) return std::nullopt;

    std::string element;  // the element being declared, with its claimed count
    std::string count;
    bool has_properties = false;
    // An element ends at the next element or at end_header: check its claim then.
    const auto claim_problem = [&]() -> std::optional<std::string> {
        if (element.empty() || !has_properties) return std::nullopt;
        const std::size_t digits = count.find_first_not_of("0123456789");
        if (count.empty() || digits != std::string::npos) return std::nullopt;  // assimp rejects
        // More than 20 digits overflows any count; otherwise compare as numbers.
        if (count.size() <= 19 && std::stoull(count) <= file_size) return std::nullopt;
        return "PLY element '" + element + "' claims " + count +
               " instances, more than the file's " + std::to_string(file_size) + " bytes can hold";
    };
    for (Line read = next_line(it, line); read != Line::none; read = next_line(it, line)) {
        const std::vector<std::string> words = words_of(line);
        const std::string keyword = words.empty() ? std::string() : words[0];
        // assimp can also loop forever when end_header is the file's last bytes (after a
        // stray line in the header; found by fuzz_mesh_import). Such a file holds no data.
        if (keyword == "end_header" && read == Line::last)
            return "a PLY file that ends at its end_header line (no data)";
        if (keyword == "end_header") return claim_problem();
        if (keyword == "element") {
            if (auto problem = claim_problem()) return problem;
            element = words.size() > 1 ? words[1] : std::string();
            count = words.size() > 2 ? words[2] : std::string();
            has_properties = false;
        } else if (keyword == "property") {
            has_properties = true;
        }
    }
    return "a PLY file whose header has no end_header line";
}

}  // namespace trackphys::detail
