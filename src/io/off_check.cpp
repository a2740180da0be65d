// check_off (mesh_checks.hpp): the OFF keyword, the counts, then every vertex and face line.

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "io/mesh_checks.hpp"
#include "io/text_scanner.hpp"

namespace trackphys::detail {
namespace {

// The header keywords whose vertex lines assimp reads as "x y z" and then skips the rest of
// (colours, normals, texture coordinates): 3-D OFF only. The 4-D and n-D variants are
// refused, since assimp reads their vertex lines differently.
bool is_off_keyword(std::string_view word) {
    for (const std::string_view k : {"OFF", "COFF", "NOFF", "CNOFF", "STOFF", "STCOFF", "STNOFF"})
        if (word == k) return true;
    return false;
}

const std::vector<std::string_view>& next_line_or_fail(TextScanner& scan, const std::string& what) {
    const std::vector<std::string_view>& words = scan.next_content_line('#');
    if (words.empty()) scan.fail("the file ends before " + what);
    return words;
}

}  // namespace

void check_off(std::string_view file) {
    TextScanner scan(file);
    const std::vector<std::string_view>& header = scan.next_content_line('#');
    if (header.size() != 1 || !is_off_keyword(header[0]))
        scan.fail("an OFF file starts with a line 'OFF' (or COFF, NOFF, CNOFF, STOFF...)");
    const std::vector<std::string_view>& counts = next_line_or_fail(scan, "the counts");
    scan.expect_words(2, 3, "the counts line");
    const std::uint64_t vertices = scan.count(counts[0], "vertex count");
    const std::uint64_t faces = scan.count(counts[1], "face count");
    if (counts.size() == 3) scan.count(counts[2], "edge count");
    // Each vertex and face takes a line: assimp allocates both counts before reading one.
    if (vertices > file.size() || faces > file.size())
        scan.fail("OFF header claims " + std::to_string(vertices) + " vertices and " +
                  std::to_string(faces) + " faces, more than the file's " +
                  std::to_string(file.size()) + " bytes can hold");
    for (std::uint64_t v = 0; v < vertices; ++v) {
        const std::vector<std::string_view>& words =
            next_line_or_fail(scan, "vertex " + std::to_string(v));
        if (words.size() < 3)
            scan.fail("vertex " + std::to_string(v) + " has fewer than 3 numbers");
        for (const std::string_view w : words) scan.real(w, "vertex " + std::to_string(v));
    }
    for (std::uint64_t f = 0; f < faces; ++f) {
        const std::string face = "face " + std::to_string(f);
        const std::vector<std::string_view>& words = next_line_or_fail(scan, face);
        const std::uint64_t n = scan.count(words[0], face + " index count");
        if (n == 0) scan.fail(face + " has no vertex index");
        if (n > words.size() - 1)
            scan.fail(face + " claims " + std::to_string(n) + " indices, the line holds " +
                      std::to_string(words.size() - 1));
        for (std::size_t k = 1; k <= n; ++k)
            if (scan.count(words[k], face + " index") >= vertices)
                scan.fail(face + ": vertex index " + std::string(words[k]) + " out of range (" +
                          std::to_string(vertices) + " vertices)");
        for (std::size_t k = n + 1; k < words.size(); ++k) scan.real(words[k], face + " colour");
    }
    if (!scan.next_content_line('#').empty()) scan.fail("data after the last OFF face");
}

}  // namespace trackphys::detail
