// check_obj (mesh_checks.hpp): every statement of a Wavefront OBJ file, every index of its
// faces, lines and points in range of what was defined before it.

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "io/mesh_checks.hpp"
#include "io/text_scanner.hpp"
#include "trackphys/error.hpp"

namespace trackphys::detail {
namespace {

// Statements assimp reads no geometry from, or names it only keeps (materials are never
// opened: confined_io_system.hpp).
constexpr std::array<std::string_view, 15> kNamingStatements{
    "o",      "g",     "s",        "usemtl",   "mtllib",     "mg",        "lod", "maplib",
    "usemap", "bevel", "c_interp", "d_interp", "shadow_obj", "trace_obj", "vp"};

// Defined so far: what a face's v/vt/vn indices may refer to.
struct Counts {
    std::int64_t v = 0;
    std::int64_t vt = 0;
    std::int64_t vn = 0;
};

// An OBJ index: 1 to count, or -1 to -count (counting back from the last one defined).
void check_index(const TextScanner& scan, std::string_view word, std::int64_t count,
                 const char* what) {
    const std::int64_t i = scan.integer(word, what);
    if (i == 0 || i > count || i < -count)
        scan.fail(std::string(what) + " " + std::string(word) + " out of range (" +
                  std::to_string(count) + " defined so far)");
}

// v, v/vt, v//vn or v/vt/vn.
void check_corner(const TextScanner& scan, std::string_view corner, const Counts& counts) {
    const std::size_t first = corner.find('/');
    check_index(scan, corner.substr(0, first), counts.v, "vertex index");
    if (first == std::string_view::npos) return;
    const std::size_t second = corner.find('/', first + 1);
    const std::string_view vt = corner.substr(first + 1, second - first - 1);
    if (!vt.empty()) check_index(scan, vt, counts.vt, "texture coordinate index");
    if (second == std::string_view::npos) {
        if (vt.empty()) scan.fail("an empty index in " + quoted_text(corner));
        return;
    }
    check_index(scan, corner.substr(second + 1), counts.vn, "normal index");
}

void check_numbers(const TextScanner& scan, const std::vector<std::string_view>& words,
                   std::size_t min, std::size_t max, const char* what) {
    if (words.size() < min + 1 || words.size() > max + 1)
        scan.fail(std::string(what) + " of " + std::to_string(words.size() - 1) +
                  " numbers, expected " + std::to_string(min) + " to " + std::to_string(max));
    for (std::size_t k = 1; k < words.size(); ++k) scan.real(words[k], what);
}

bool is_naming(std::string_view keyword) {
    for (const std::string_view k : kNamingStatements)
        if (keyword == k) return true;
    return false;
}

}  // namespace

void check_obj(std::string_view file) {
    TextScanner scan(file);
    Counts counts;
    while (!scan.at_end()) {
        const std::vector<std::string_view>& words = scan.next_line();
        if (words.empty() || words[0][0] == '#') continue;
        if (words.back().back() == '\\') scan.fail("a line continued with '\\' (not read)");
        const std::string_view keyword = words[0];
        if (keyword == "v") {
            check_numbers(scan, words, 3, 7, "a vertex");  // x y z, w or r g b (+ a)
            ++counts.v;
        } else if (keyword == "vt") {
            check_numbers(scan, words, 1, 3, "a texture coordinate");
            ++counts.vt;
        } else if (keyword == "vn") {
            check_numbers(scan, words, 3, 3, "a normal");
            ++counts.vn;
        } else if (keyword == "f" || keyword == "l" || keyword == "p") {
            if (keyword == "f" && words.size() < 4) scan.fail("a face of fewer than 3 corners");
            if (words.size() < 2) scan.fail("a line or point without an index");
            for (std::size_t k = 1; k < words.size(); ++k) check_corner(scan, words[k], counts);
        } else if (!is_naming(keyword)) {
            scan.fail("the statement " + quoted_text(keyword) +
                      " is not read (free-form curves and surfaces are not collision geometry)");
        }
    }
}

}  // namespace trackphys::detail
