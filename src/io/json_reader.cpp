#include "json_reader.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>

#include "trackphys/error.hpp"
#include "trackphys/io/regular_file.hpp"

namespace trackphys::json_io {
namespace {

namespace fs = std::filesystem;

// Where the check is while it reads: one frame per open object or array, so that a key
// given twice, a number out of range and nesting too deep can be reported with a path.
struct Frame {
    bool object = true;
    std::vector<std::string> keys;  // object: keys seen so far
    std::size_t elements = 0;       // array: elements begun so far
};

std::string frames_path(const std::vector<Frame>& frames) {
    std::string path;
    // Every frame but the innermost has begun the value that holds the next frame.
    for (std::size_t i = 0; i + 1 < frames.size(); ++i)
        path = frames[i].object ? join_path(path, frames[i].keys.back())
                                : index_path(path, frames[i].elements - 1);
    return path;
}

// The path of the value being read: the innermost object's last key, or its array's next
// element.
std::string reading_path(const std::vector<Frame>& frames) {
    if (frames.empty()) return {};
    const Frame& inner = frames.back();
    if (!inner.object) return index_path(frames_path(frames), inner.elements);
    return inner.keys.empty() ? frames_path(frames)
                              : join_path(frames_path(frames), inner.keys.back());
}

// "line L, column C" of text[offset], both from 1, as nlohmann counts them.
std::string line_and_column(std::string_view text, std::size_t offset) {
    const std::string_view before = text.substr(0, offset);
    const std::size_t line_start = before.rfind('\n');
    const std::size_t column =
        line_start == std::string_view::npos ? offset + 1 : offset - line_start;
    return "line " + std::to_string(std::count(before.begin(), before.end(), '\n') + 1) +
           ", column " + std::to_string(column);
}

// nlohmann's messages start with "[json.exception.parse_error.101] ": keep what follows.
std::string without_exception_id(const std::string& what) {
    const std::size_t end = what.find("] ");
    return what.rfind("[json.exception.", 0) == 0 && end != std::string::npos ? what.substr(end + 2)
                                                                              : what;
}

std::string describe(const Json& value) {
    if (value.is_number_integer() || value.is_number_float()) return "the number " + value.dump();
    if (value.is_string()) return "the string " + value.dump();
    if (value.is_array()) return "an array";
    if (value.is_object()) return "an object";
    return value.is_null() ? "null" : "a boolean";
}

// A SAX pass that refuses, with the path of each, a key given twice, nesting beyond
// max_json_depth, an object of more than max_json_object_keys keys and more than
// max_json_values values; and reports nlohmann's parse errors as trackphys::Error.
class StructureCheck {
  public:
    explicit StructureCheck(const std::string& source) : source_(source) {}

    bool null() { return value(); }
    bool boolean(bool) { return value(); }
    bool number_integer(Json::number_integer_t) { return value(); }
    bool number_unsigned(Json::number_unsigned_t) { return value(); }
    bool number_float(Json::number_float_t, const Json::string_t&) { return value(); }
    bool string(Json::string_t&) { return value(); }
    bool binary(Json::binary_t&) { return value(); }
    bool start_object(std::size_t) { return open(true); }
    bool start_array(std::size_t) { return open(false); }
    bool end_object() { return close(); }
    bool end_array() { return close(); }

    bool key(Json::string_t& key) {
        std::vector<std::string>& keys = frames_.back().keys;
        if (std::find(keys.begin(), keys.end(), key) != keys.end())
            fail(source_, "", "duplicate key " + quoted_text(key) + " in " + object_name());
        if (keys.size() == max_json_object_keys)
            fail(
                source_, "",
                object_name() + " has more than " + std::to_string(max_json_object_keys) + " keys");
        keys.push_back(key);
        return true;
    }

    bool parse_error(std::size_t, const std::string&, const Json::exception& e) {
        // "parse error at line 3, column 7: syntax error while parsing object - ...", or a
        // number too large for a double (out_of_range.406), which has no position.
        const bool overflow = e.id == 406;
        throw Error(source_ + ": malformed JSON" +
                    (overflow && !frames_.empty() ? " at " + reading_path(frames_) : "") + ", " +
                    without_exception_id(e.what()));
    }

  private:
    // A plain value or a container begins the next element of an enclosing array.
    bool value() {
        if (++values_ > max_json_values)
            fail(source_, "", "more than " + std::to_string(max_json_values) + " values");
        if (!frames_.empty() && !frames_.back().object) ++frames_.back().elements;
        return true;
    }
    bool open(bool object) {
        value();
        frames_.push_back({object, {}, 0});
        if (frames_.size() > max_json_depth)
            fail(source_, frames_path(frames_),
                 "nested deeper than " + std::to_string(max_json_depth) + " levels");
        return true;
    }
    bool close() {
        frames_.pop_back();
        return true;
    }
    std::string object_name() const {
        const std::string where = frames_path(frames_);
        return where.empty() ? "the top-level object" : where;
    }

    const std::string& source_;
    std::vector<Frame> frames_;
    std::size_t values_ = 0;
};

}  // namespace

std::string join_path(const std::string& parent, std::string_view key) {
    std::string path = parent;
    if (!path.empty()) path += '.';
    path += key;
    return path;
}

std::string index_path(const std::string& parent, std::size_t index) {
    return parent + "[" + std::to_string(index) + "]";
}

void fail(const std::string& source, const std::string& path, const std::string& reason) {
    throw Error(source + ": " + (path.empty() ? "" : path + ": ") + reason);
}

std::string read_text_file(const fs::path& path, const char* what) {
    const std::string name = std::string(what) + " '" + path.string() + "'";
    require_regular_file(path, name);
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(name + ": cannot open it for reading");
    std::string text;
    char buffer[65536];
    while (in.read(buffer, sizeof buffer) || in.gcount() > 0) {
        text.append(buffer, static_cast<std::size_t>(in.gcount()));
        if (text.size() > max_file_bytes)
            throw Error(name + ": larger than " + std::to_string(max_file_bytes >> 20) + " MiB");
    }
    if (in.bad()) throw Error(name + ": read error");
    if (text.empty()) throw Error(name + ": the file is empty");
    return text;
}

Json parse_document(std::string_view text, const std::string& source) {
    // nlohmann's lexer reads a NUL byte as the end of the input, so what follows one would
    // go unread rather than be refused as trailing text.
    if (const std::size_t nul = text.find('\0'); nul != std::string_view::npos)
        throw Error(source + ": malformed JSON, a NUL byte at " + line_and_column(text, nul));
    // Checked first without building anything: the document built after it is then bounded
    // (256 keys searched at an insert at most, about 75 bytes of memory a value), and
    // nlohmann's parser with a callback, which could check while building, searches the
    // enclosing array at the end of each object (hours for a file of 2 million "{}").
    StructureCheck check(source);
    Json::sax_parse(text.begin(), text.end(), &check);
    return Json::parse(text.begin(), text.end());
}

double to_number(const Json& value, const std::string& path, const std::string& source) {
    if (!value.is_number()) fail(source, path, "expected a number, got " + describe(value));
    const double x = value.get<double>();
    if (!std::isfinite(x)) fail(source, path, "the number must be finite, got " + value.dump());
    return x;
}

std::vector<double> to_numbers(const Json& value, std::size_t n, const std::string& path,
                               const std::string& source) {
    if (!value.is_array() || value.size() != n)
        fail(source, path,
             "expected an array of " + std::to_string(n) + " numbers, got " +
                 (value.is_array() ? "an array of " + std::to_string(value.size())
                                   : describe(value)));
    std::vector<double> numbers;
    for (std::size_t i = 0; i < n; ++i)
        numbers.push_back(to_number(value[i], index_path(path, i), source));
    return numbers;
}

ObjectReader::ObjectReader(const Json& value, std::string path, std::string source)
    : value_(value), path_(std::move(path)), source_(std::move(source)) {
    if (!value_.is_object()) fail(source_, path_, "expected an object, got " + describe(value_));
}

bool ObjectReader::has(std::string_view key) { return find(key) != nullptr; }

const Json* ObjectReader::find(std::string_view key) {
    if (std::find(known_.begin(), known_.end(), key) == known_.end()) known_.emplace_back(key);
    const auto it = value_.find(key);
    return it == value_.end() ? nullptr : &*it;
}

const Json& ObjectReader::require(std::string_view key) {
    const Json* value = find(key);
    if (value == nullptr) fail(source_, path_, "missing key '" + std::string(key) + "'");
    return *value;
}

void ObjectReader::read(std::string_view key, double& out) {
    if (const Json* value = find(key)) out = to_number(*value, path_of(key), source_);
}

void ObjectReader::read(std::string_view key, std::uint64_t& out) {
    const Json* value = find(key);
    if (value == nullptr) return;
    if (value->is_number_unsigned())
        out = value->get<std::uint64_t>();
    else if (value->is_number_integer() && value->get<std::int64_t>() == 0)
        out = 0;  // "-0", which nlohmann reads as a signed integer
    else if (value->is_number_integer())
        fail(source_, path_of(key), "must be >= 0, got " + value->dump());
    else
        fail(source_, path_of(key), "expected a whole number, got " + describe(*value));
}

void ObjectReader::read(std::string_view key, int& out) {
    const Json* value = find(key);
    if (value == nullptr) return;
    const bool fits = value->is_number_unsigned()
                          ? value->get<std::uint64_t>() <=
                                static_cast<std::uint64_t>(std::numeric_limits<int>::max())
                          : value->is_number_integer() &&
                                value->get<std::int64_t>() >= std::numeric_limits<int>::min();
    if (!fits)
        fail(source_, path_of(key),
             "expected a whole number in int's range, got " + describe(*value));
    out = value->get<int>();
}

void ObjectReader::read(std::string_view key, glm::dvec3& out) {
    if (const Json* value = find(key)) {
        const std::vector<double> v = to_numbers(*value, 3, path_of(key), source_);
        out = {v[0], v[1], v[2]};
    }
}

void ObjectReader::read(std::string_view key, glm::dquat& out) {
    if (const Json* value = find(key)) {
        const std::vector<double> v = to_numbers(*value, 4, path_of(key), source_);
        out = glm::dquat(v[0], v[1], v[2], v[3]);  // w, x, y, z
    }
}

void ObjectReader::read(std::string_view key, std::string& out) {
    const Json* value = find(key);
    if (value == nullptr) return;
    if (!value->is_string())
        fail(source_, path_of(key), "expected a string, got " + describe(*value));
    out = value->get<std::string>();
}

void ObjectReader::finish() const {
    for (const auto& [key, ignored] : value_.items()) {
        if (std::find(known_.begin(), known_.end(), key) != known_.end()) continue;
        std::string expected;
        for (const std::string& k : known_) expected += (expected.empty() ? "" : ", ") + k;
        fail(source_, path_,
             "unknown key " + quoted_text(key) +
                 (expected.empty() ? "" : " (expected one of: " + expected + ")"));
    }
}

}  // namespace trackphys::json_io
