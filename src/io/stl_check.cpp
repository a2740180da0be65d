// check_stl (mesh_checks.hpp): a binary STL's triangle count against its size, or an ASCII
// STL's every facet.

#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>
#include <vector>

#include "io/mesh_checks.hpp"
#include "io/text_scanner.hpp"
#include "trackphys/error.hpp"

namespace trackphys::detail {
namespace {

constexpr std::size_t kBinaryHeader = 84;  // 80 free bytes and a 32-bit triangle count
constexpr std::size_t kBinaryTriangle = 50;

// assimp takes a file as binary STL exactly when its size is 84 + 50 * the count it
// declares, whatever its first bytes say: such a file holds every triangle it claims.
bool is_binary(std::string_view file) {
    if (file.size() < kBinaryHeader) return false;
    std::uint32_t count = 0;
    for (int k = 3; k >= 0; --k)
        count = (count << 8) | static_cast<unsigned char>(file[80 + static_cast<std::size_t>(k)]);
    return file.size() == kBinaryHeader + std::uint64_t{count} * kBinaryTriangle;
}

// The next line, which must start with keyword.
const std::vector<std::string_view>& expect_keyword(TextScanner& scan, std::string_view keyword) {
    const std::vector<std::string_view>& words = scan.next_content_line();
    if (words.empty() || words[0] != keyword)
        scan.fail(
            "expected " + quoted_text(keyword) +
            (words.empty() ? std::string(", the file ends") : ", found " + quoted_text(words[0])));
    return words;
}

void expect_vector(TextScanner& scan, const std::vector<std::string_view>& words, std::size_t first,
                   std::string_view what) {
    scan.expect_words(first + 3, first + 3, what);
    for (std::size_t k = first; k < first + 3; ++k) scan.real(words[k], what);
}

// solid [name], then facets of exactly three vertices, then endsolid [name]; several solids
// may follow each other.
void check_ascii(std::string_view file) {
    TextScanner scan(file);
    std::size_t facets = 0;
    while (!scan.next_content_line().empty()) {
        if (scan.words()[0] != "solid") scan.fail("expected 'solid'");
        for (;;) {
            const std::vector<std::string_view>& line = scan.next_content_line();
            if (line.empty()) scan.fail("the file ends before 'endsolid'");
            if (line[0] == "endsolid") break;
            if (line[0] != "facet") scan.fail("expected 'facet' or 'endsolid'");
            if (line.size() < 2 || line[1] != "normal") scan.fail("expected 'facet normal'");
            expect_vector(scan, line, 2, "facet normal");
            const std::vector<std::string_view>& outer = expect_keyword(scan, "outer");
            if (outer.size() != 2 || outer[1] != "loop") scan.fail("expected 'outer loop'");
            for (int corner = 0; corner < 3; ++corner)
                expect_vector(scan, expect_keyword(scan, "vertex"), 1, "vertex");
            expect_keyword(scan, "endloop");
            expect_keyword(scan, "endfacet");
            ++facets;
        }
    }
    if (facets == 0) scan.fail("an ASCII STL without a facet");
}

}  // namespace

void check_stl(std::string_view file) {
    if (is_binary(file)) return;
    try {
        check_ascii(file);
    } catch (const MeshCheckError& e) {
        throw MeshCheckError{
            "not a binary STL (its size is not 84 + 50 x the triangle count "
            "at byte 80), and as ASCII STL: " +
            e.reason};
    }
}

}  // namespace trackphys::detail
