// check_ac3d (mesh_checks.hpp): the header, the materials, then every object, its vertices,
// its surfaces and their references, and its kids, iteratively (a hostile file can nest
// deeply, and assimp's reader recurses once per level).

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "io/mesh_checks.hpp"
#include "io/text_scanner.hpp"
#include "trackphys/error.hpp"

namespace trackphys::detail {
namespace {

// The low four bits of a SURF's flags: its kind, and the fewest references assimp can make
// it from (a triangle strip of one reference writes past assimp's buffer: issue 19).
struct SurfaceKind {
    unsigned type;
    std::uint64_t min_refs;
    const char* name;
};
constexpr SurfaceKind kSurfaceKinds[] = {
    {0, 3, "polygon"}, {1, 2, "closed line"}, {2, 2, "line"}, {4, 3, "triangle strip"}};

const std::vector<std::string_view>& next_or_fail(TextScanner& scan, const std::string& what) {
    const std::vector<std::string_view>& words = scan.next_content_line();
    if (words.empty()) scan.fail("the file ends before " + what);
    return words;
}

void check_reals(TextScanner& scan, std::size_t count, const char* what) {
    const std::vector<std::string_view>& words = scan.words();
    scan.expect_words(count + 1, count + 1, what);
    for (std::size_t k = 1; k < words.size(); ++k) scan.real(words[k], what);
}

const SurfaceKind& surface_kind(TextScanner& scan) {
    scan.expect_words(2, 2, "SURF");
    const std::string_view flags = scan.words()[1];
    if (flags.size() < 3 || flags.size() > 10 || flags.substr(0, 2) != "0x" ||
        flags.find_first_not_of("0123456789abcdefABCDEF", 2) != std::string_view::npos)
        scan.fail("SURF flags " + quoted_text(flags) + " are not hexadecimal 0x...");
    const unsigned type = std::stoul(std::string(flags.substr(2)), nullptr, 16) & 0xfu;
    for (const SurfaceKind& kind : kSurfaceKinds)
        if (kind.type == type) return kind;
    scan.fail("SURF flags " + quoted_text(flags) + ": unknown surface type " +
              std::to_string(type));
}

void check_surface(TextScanner& scan, std::uint64_t vertices) {
    next_or_fail(scan, "a surface");
    if (scan.words()[0] != "SURF") scan.fail("expected 'SURF'");
    const SurfaceKind& kind = surface_kind(scan);
    for (;;) {
        const std::vector<std::string_view>& words = next_or_fail(scan, "'refs'");
        if (words[0] == "refs") break;
        if (words[0] != "mat") scan.fail("expected 'mat' or 'refs'");
        scan.expect_words(2, 2, "mat");
        scan.count(words[1], "material index");
    }
    scan.expect_words(2, 2, "refs");
    const std::uint64_t refs = scan.count(scan.words()[1], "reference count");
    if (refs < kind.min_refs)
        scan.fail(std::string("a ") + kind.name + " of " + std::to_string(refs) +
                  " references (at least " + std::to_string(kind.min_refs) + ")");
    for (std::uint64_t r = 0; r < refs; ++r) {
        const std::vector<std::string_view>& words = next_or_fail(scan, "a reference");
        if (scan.count(words[0], "vertex index") >= vertices)
            scan.fail("vertex index " + std::string(words[0]) + " out of range (" +
                      std::to_string(vertices) + " vertices)");
        for (std::size_t k = 1; k < words.size(); ++k) scan.real(words[k], "texture coordinate");
    }
}

// The body of an OBJECT, through its kids line; returns how many kids follow.
std::uint64_t check_object(TextScanner& scan, std::size_t bytes) {
    std::uint64_t vertices = 0;
    for (;;) {
        const std::vector<std::string_view>& words = next_or_fail(scan, "'kids'");
        const std::string_view keyword = words[0];
        if (keyword == "kids") {
            scan.expect_words(2, 2, "kids");
            return scan.count(words[1], "kids count", bytes);
        }
        if (keyword == "numvert") {
            scan.expect_words(2, 2, "numvert");
            vertices = scan.count(words[1], "vertex count", bytes);
            for (std::uint64_t v = 0; v < vertices; ++v) {
                const std::size_t numbers =
                    next_or_fail(scan, "vertex " + std::to_string(v)).size();
                // x y z, and a normal in some writers' files
                if (numbers != 3 && numbers != 6)
                    scan.fail("vertex " + std::to_string(v) + " has " + std::to_string(numbers) +
                              " numbers, not 3 (or 6 with a normal)");
                for (const std::string_view w : scan.words()) scan.real(w, "a vertex");
            }
        } else if (keyword == "numsurf") {
            scan.expect_words(2, 2, "numsurf");
            const std::uint64_t surfaces = scan.count(words[1], "surface count", bytes);
            for (std::uint64_t s = 0; s < surfaces; ++s) check_surface(scan, vertices);
        } else if (keyword == "data") {
            scan.expect_words(2, 2, "data");
            if (!scan.skip_bytes(scan.count(words[1], "data length")))
                scan.fail("data runs past the file");
        } else if (keyword == "rot") {
            check_reals(scan, 9, "rot");
        } else if (keyword == "loc") {
            check_reals(scan, 3, "loc");
        } else if (keyword == "texrep" || keyword == "texoff") {
            check_reals(scan, 2, "texrep or texoff");
        } else if (keyword != "name" && keyword != "texture" && keyword != "url" &&
                   keyword != "crease" && keyword != "subdiv" && keyword != "hidden" &&
                   keyword != "locked" && keyword != "folded") {
            scan.fail("unknown AC3D object line " + quoted_text(keyword));
        }
    }
}

}  // namespace

void check_ac3d(std::string_view file, std::size_t max_nesting) {
    TextScanner scan(file);
    const std::vector<std::string_view>& header = scan.next_content_line();
    if (header.size() != 1 || header[0].substr(0, 4) != "AC3D")
        scan.fail("an AC3D file starts with a line 'AC3D' and its version");
    std::vector<std::uint64_t> kids_left;  // per open level: kids still to come
    bool any_object = false;
    for (const std::vector<std::string_view>* words = &scan.next_content_line(); !words->empty();
         words = &scan.next_content_line()) {
        if ((*words)[0] == "MATERIAL" && !any_object) continue;
        if ((*words)[0] != "OBJECT") scan.fail("expected 'OBJECT'");
        scan.expect_words(2, 2, "OBJECT");
        any_object = true;
        if (!kids_left.empty()) --kids_left.back();
        const std::uint64_t kids = check_object(scan, file.size());
        if (kids > 0) {
            kids_left.push_back(kids);
            if (kids_left.size() > max_nesting)
                scan.fail("objects nested deeper than " + std::to_string(max_nesting) +
                          ", the limit max_nesting");
        }
        while (!kids_left.empty() && kids_left.back() == 0) kids_left.pop_back();
    }
    // Kids still missing at the end are no error: real tracks claim more than they hold
    // (TORCS's g-track-1 ends 30 short), and assimp reads what is there.
    if (!any_object) scan.fail("an AC3D file without an OBJECT");
}

}  // namespace trackphys::detail
