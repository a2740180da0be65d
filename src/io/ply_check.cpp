// check_ply (mesh_checks.hpp): the header, then every element instance of the body, ASCII
// or binary, against the header's declarations.

#include <array>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "io/mesh_checks.hpp"
#include "io/text_scanner.hpp"
#include "trackphys/error.hpp"

namespace trackphys::detail {
namespace {

struct ScalarType {
    std::string_view name;
    std::size_t bytes;
    bool is_signed;
    bool is_integer;
};

constexpr std::array<ScalarType, 16> kTypes{{
    {"char", 1, true, true},
    {"int8", 1, true, true},
    {"uchar", 1, false, true},
    {"uint8", 1, false, true},
    {"short", 2, true, true},
    {"int16", 2, true, true},
    {"ushort", 2, false, true},
    {"uint16", 2, false, true},
    {"int", 4, true, true},
    {"int32", 4, true, true},
    {"uint", 4, false, true},
    {"uint32", 4, false, true},
    {"float", 4, true, false},
    {"float32", 4, true, false},
    {"double", 8, true, false},
    {"float64", 8, true, false},
}};

struct Property {
    std::string_view name;
    const ScalarType* type = nullptr;        // of the value, or of a list's items
    const ScalarType* count_type = nullptr;  // a list's count; null for a scalar
};

// Which values are vertex indices, and the smallest one allowed: a face's corners, or a
// triangle strip's (where -1 restarts the strip).
struct IndexRule {
    bool applies = false;
    std::int64_t min = 0;
};

struct Element {
    std::string_view name;
    std::uint64_t count = 0;
    std::vector<Property> properties;
};

enum class Encoding { ascii, little_endian, big_endian };

struct Header {
    Encoding encoding = Encoding::ascii;
    std::vector<Element> elements;
    std::size_t body = 0;          // byte offset of the first instance
    std::size_t header_lines = 0;  // for an ASCII body's line numbers
};

std::int64_t min_of(const ScalarType& t) {
    return t.is_signed ? -(std::int64_t{1} << (8 * t.bytes - 1)) : 0;
}
std::int64_t max_of(const ScalarType& t) {
    return t.is_signed ? (std::int64_t{1} << (8 * t.bytes - 1)) - 1
                       : (std::int64_t{1} << (8 * t.bytes)) - 1;
}

IndexRule index_rule(std::string_view element, std::string_view property) {
    if (property != "vertex_indices" && property != "vertex_index") return {};
    if (element == "face") return {true, 0};
    if (element == "tristrips") return {true, -1};
    return {};
}

const ScalarType& type_named(const TextScanner& scan, std::string_view name) {
    for (const ScalarType& t : kTypes)
        if (t.name == name) return t;
    scan.fail("unknown PLY property type " + quoted_text(name));
}

bool is_face_element(std::string_view name) { return name == "face" || name == "tristrips"; }

Header read_header(std::string_view file) {
    TextScanner scan(file);
    if (scan.at_end() || scan.next_line() != std::vector<std::string_view>{"ply"})
        scan.fail("a PLY file starts with a line 'ply'");
    Header header;
    bool has_format = false;
    for (;;) {
        if (scan.at_end()) scan.fail("the PLY header has no end_header line");
        const std::vector<std::string_view>& words = scan.next_line();
        const std::string_view keyword = words.empty() ? std::string_view() : words[0];
        if (keyword == "comment" || keyword == "obj_info") continue;
        if (keyword == "end_header") {
            scan.expect_words(1, 1, "end_header");
            break;
        }
        if (keyword == "format") {
            scan.expect_words(3, 3, "format");
            if (has_format) scan.fail("a second format line");
            has_format = true;
            if (words[2] != "1.0") scan.fail("PLY version " + quoted_text(words[2]));
            if (words[1] == "ascii")
                header.encoding = Encoding::ascii;
            else if (words[1] == "binary_little_endian")
                header.encoding = Encoding::little_endian;
            else if (words[1] == "binary_big_endian")
                header.encoding = Encoding::big_endian;
            else
                scan.fail("unknown PLY format " + quoted_text(words[1]));
        } else if (keyword == "element") {
            scan.expect_words(3, 3, "element");
            // assimp sizes the vertex or face array by an element's first declaration and
            // writes a later one's instances into it, past its end (found by fuzz_mesh_import);
            // faces and triangle strips share one array that way, so a file holds one kind.
            for (const Element& e : header.elements) {
                if (e.name == words[1]) scan.fail("a second element " + quoted_text(words[1]));
                if (is_face_element(e.name) && is_face_element(words[1]))
                    scan.fail("an element " + quoted_text(words[1]) + " besides " +
                              quoted_text(e.name) + " (faces or triangle strips, not both)");
            }
            header.elements.push_back({words[1], scan.count(words[2], "element count"), {}});
        } else if (keyword == "property") {
            if (header.elements.empty()) scan.fail("a property before any element");
            Property property;
            if (words.size() > 1 && words[1] == "list") {
                scan.expect_words(5, 5, "list property");
                property.count_type = &type_named(scan, words[2]);
                if (!property.count_type->is_integer)
                    scan.fail("a list count of type " + quoted_text(words[2]));
                property.type = &type_named(scan, words[3]);
                property.name = words[4];
            } else {
                scan.expect_words(3, 3, "property");
                property.type = &type_named(scan, words[1]);
                property.name = words[2];
            }
            Element& element = header.elements.back();
            if (index_rule(element.name, property.name).applies && !property.type->is_integer)
                scan.fail("vertex indices of type " + quoted_text(property.type->name));
            element.properties.push_back(property);
        } else {
            scan.fail("unknown PLY header line " + quoted_text(keyword));
        }
    }
    if (!has_format) scan.fail("the PLY header has no format line");
    header.body = scan.offset();
    header.header_lines = scan.line_number();
    // assimp's reader can loop forever on such a file (found by fuzz_mesh_import).
    if (header.body >= file.size()) scan.fail("the PLY file ends at its end_header line (no data)");
    if (header.encoding != Encoding::ascii && file[header.body - 2] == '\r')
        scan.fail("a binary PLY header's end_header line ends in \"\\r\\n\", not \"\\n\"");
    // Each instance of an element with properties takes at least a byte; an element without
    // any would still make assimp allocate an instance record per claimed instance.
    for (const Element& e : header.elements) {
        if (e.count > 0 && e.properties.empty())
            throw MeshCheckError{"PLY element " + quoted_text(e.name) + " claims " +
                                 std::to_string(e.count) + " instances but has no properties"};
        if (e.count > file.size() - header.body)
            throw MeshCheckError{"PLY element " + quoted_text(e.name) + " claims " +
                                 std::to_string(e.count) + " instances, more than the " +
                                 std::to_string(file.size() - header.body) +
                                 " bytes after the header can hold"};
    }
    return header;
}

std::uint64_t vertex_count(const Header& header) {
    for (const Element& e : header.elements)
        if (e.name == "vertex") return e.count;
    return 0;
}

std::string place(const Element& e, std::uint64_t instance, const Property& p) {
    return "PLY element " + quoted_text(e.name) + " " + std::to_string(instance) + ", property " +
           quoted_text(p.name);
}

// Why index breaks rule, or empty when it does not.
std::string index_problem(std::int64_t index, IndexRule rule, std::uint64_t vertices) {
    if (index >= rule.min && (index < 0 || static_cast<std::uint64_t>(index) < vertices)) return {};
    return "vertex index " + std::to_string(index) + " out of range (" + std::to_string(vertices) +
           " vertices)";
}

void check_ascii_body(std::string_view file, const Header& header) {
    const std::uint64_t vertices = vertex_count(header);
    TextScanner scan(file.substr(header.body), header.header_lines);
    const auto value = [&scan](std::string_view word, const ScalarType& type,
                               const std::string& where) -> std::int64_t {
        if (!type.is_integer) {
            scan.real(word, where);
            return 0;
        }
        const std::int64_t v = scan.integer(word, where);
        if (v < min_of(type) || v > max_of(type))
            scan.fail(where + ": " + std::to_string(v) + " does not fit its type '" +
                      std::string(type.name) + "'");
        return v;
    };
    for (const Element& e : header.elements) {
        for (std::uint64_t i = 0; i < e.count; ++i) {
            if (scan.at_end())
                scan.fail("the file ends before PLY element " + quoted_text(e.name) + " " +
                          std::to_string(i));
            const std::vector<std::string_view>& words = scan.next_line();
            std::size_t w = 0;
            for (const Property& p : e.properties) {
                const std::string where = place(e, i, p);
                if (w >= words.size()) scan.fail(where + " is missing");
                if (p.count_type == nullptr) {
                    value(words[w++], *p.type, where);
                    continue;
                }
                const std::int64_t n = value(words[w++], *p.count_type, where + " count");
                if (n < 0) scan.fail(where + ": a negative list count");
                const IndexRule rule = index_rule(e.name, p.name);
                if (rule.applies && n == 0) scan.fail(where + ": a face of no vertex index");
                if (static_cast<std::uint64_t>(n) > words.size() - w)
                    scan.fail(where + ": the list claims " + std::to_string(n) +
                              " items, the line holds " + std::to_string(words.size() - w));
                for (std::int64_t k = 0; k < n; ++k) {
                    const std::int64_t v = value(words[w++], *p.type, where);
                    if (!rule.applies) continue;
                    const std::string problem = index_problem(v, rule, vertices);
                    if (!problem.empty()) scan.fail(where + ": " + problem);
                }
            }
            if (w != words.size())
                scan.fail("more values than PLY element " + quoted_text(e.name) + " declares");
        }
    }
    while (!scan.at_end())
        if (!scan.next_line().empty()) scan.fail("data after the last PLY element");
}

// A binary body as a cursor over its bytes; every read is checked against the end first.
class BinaryBody {
  public:
    BinaryBody(std::string_view file, std::size_t start, bool big_endian)
        : file_(file), at_(start), big_endian_(big_endian) {}

    std::size_t offset() const { return at_; }

    // Skips count values of type; false when the file ends first.
    bool skip(std::uint64_t count, const ScalarType& type) {
        if (count > (file_.size() - at_) / type.bytes) return false;
        at_ += static_cast<std::size_t>(count * type.bytes);
        return true;
    }

    // Reads an integer of type; false when the file ends first.
    bool read(const ScalarType& type, std::int64_t& value) {
        if (type.bytes > file_.size() - at_) return false;
        std::uint64_t bits = 0;
        for (std::size_t k = 0; k < type.bytes; ++k) {
            const std::size_t byte = big_endian_ ? k : type.bytes - 1 - k;
            bits = (bits << 8) | static_cast<unsigned char>(file_[at_ + byte]);
        }
        at_ += type.bytes;
        const std::uint64_t sign = std::uint64_t{1} << (8 * type.bytes - 1);
        value = type.is_signed && (bits & sign) != 0
                    ? static_cast<std::int64_t>(bits) - static_cast<std::int64_t>(sign << 1)
                    : static_cast<std::int64_t>(bits);
        return true;
    }

  private:
    std::string_view file_;
    std::size_t at_;
    bool big_endian_;
};

void check_binary_body(std::string_view file, const Header& header) {
    const std::uint64_t vertices = vertex_count(header);
    BinaryBody body(file, header.body, header.encoding == Encoding::big_endian);
    for (const Element& e : header.elements) {
        for (std::uint64_t i = 0; i < e.count; ++i) {
            for (const Property& p : e.properties) {
                const auto fail = [&](const std::string& what) {
                    throw MeshCheckError{"byte " + std::to_string(body.offset()) + ", " +
                                         place(e, i, p) + ": " + what};
                };
                if (p.count_type == nullptr) {
                    if (!body.skip(1, *p.type)) fail("the file ends here");
                    continue;
                }
                std::int64_t n = 0;
                if (!body.read(*p.count_type, n)) fail("the file ends here");
                if (n < 0) fail("a negative list count");
                const IndexRule rule = index_rule(e.name, p.name);
                if (rule.applies && n == 0) fail("a face of no vertex index");
                if (!rule.applies) {
                    if (!body.skip(static_cast<std::uint64_t>(n), *p.type))
                        fail("the list of " + std::to_string(n) + " items runs past the file");
                    continue;
                }
                for (std::int64_t k = 0; k < n; ++k) {
                    std::int64_t v = 0;
                    if (!body.read(*p.type, v))
                        fail("the list of " + std::to_string(n) + " items runs past the file");
                    const std::string problem = index_problem(v, rule, vertices);
                    if (!problem.empty()) fail(problem);
                }
            }
        }
    }
}

}  // namespace

void check_ply(std::string_view file) {
    const Header header = read_header(file);
    if (header.encoding == Encoding::ascii)
        check_ascii_body(file, header);
    else
        check_binary_body(file, header);
}

}  // namespace trackphys::detail
