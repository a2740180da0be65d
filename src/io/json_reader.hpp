#pragma once

// Reading trackphys's JSON files (car specs, scenarios) strictly: malformed text is reported
// with its line and column, every value with the JSON path that leads to it
// ("ellipsoids[2].semi_axes"), and a key nobody asked for, or the same key twice, is an
// error rather than something silently ignored (a typo in a key would otherwise leave the
// default in place without a word).

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include <glm/gtc/quaternion.hpp>
#include <glm/vec3.hpp>
#include <nlohmann/json.hpp>

namespace trackphys::json_io {

/// Objects keep the order of the file, so messages list keys and files are written in a
/// readable order.
using Json = nlohmann::ordered_json;

/// A file larger than this is not a car spec or a scenario (bytes).
inline constexpr std::uintmax_t max_file_bytes = 16u << 20;

/// Deeper nesting, an object of more keys or a document of more values is refused: no car
/// spec or scenario comes near (5 levels, 21 keys, a few hundred values), and they bound the
/// time and memory a hostile file's parse takes.
inline constexpr std::size_t max_json_depth = 64;
inline constexpr std::size_t max_json_object_keys = 256;
inline constexpr std::size_t max_json_values = std::size_t{1} << 20;

/// The whole file as text. Throws trackphys::Error "<what> '<path>': <reason>" when it is
/// missing, a folder or another non-regular file (a device, a pipe), unreadable, empty or
/// larger than max_file_bytes.
std::string read_text_file(const std::filesystem::path& path, const char* what);

/// One JSON document. Throws trackphys::Error "<source>: malformed JSON, parse error at line
/// L, column C: ..." for bad syntax ("a NUL byte at line L, column C" for that byte),
/// "<source>: duplicate key 'k' in <path>" for a key given twice, and refuses nesting or
/// objects beyond the bounds above.
Json parse_document(std::string_view text, const std::string& source);

/// "a.b" / "a[2]" / "b" at the root.
std::string join_path(const std::string& parent, std::string_view key);
std::string index_path(const std::string& parent, std::size_t index);

/// Throws trackphys::Error "<source>: <path>: <reason>" (or "<source>: <reason>" at the root).
[[noreturn]] void fail(const std::string& source, const std::string& path,
                       const std::string& reason);

/// One JSON object being read. Each read names the key it looks for; a key that is absent
/// leaves the destination as it was (the documented default). finish() rejects every key of
/// the object that no read named, listing the ones it knows.
class ObjectReader {
  public:
    /// Throws when value is not an object.
    ObjectReader(const Json& value, std::string path, std::string source);

    bool has(std::string_view key);
    /// The value of key, nullptr when absent (the key counts as known either way).
    const Json* find(std::string_view key);
    /// The value of key; throws "missing key" when absent.
    const Json& require(std::string_view key);

    /// A finite number.
    void read(std::string_view key, double& out);
    /// A non-negative integer.
    void read(std::string_view key, std::uint64_t& out);
    /// An integer in int's range.
    void read(std::string_view key, int& out);
    /// An array of three finite numbers.
    void read(std::string_view key, glm::dvec3& out);
    /// An array of four finite numbers [w, x, y, z].
    void read(std::string_view key, glm::dquat& out);
    void read(std::string_view key, std::string& out);

    /// The path of key in this object, for messages and nested readers.
    std::string path_of(std::string_view key) const { return join_path(path_, key); }
    const std::string& path() const { return path_; }
    const std::string& source() const { return source_; }

    /// Throws for the first key of the object that no read above named.
    void finish() const;

  private:
    const Json& value_;
    std::string path_;
    std::string source_;
    std::vector<std::string> known_;
};

/// The number at path as a finite double; throws naming path otherwise.
double to_number(const Json& value, const std::string& path, const std::string& source);
/// The array at path as n finite numbers; throws naming path otherwise.
std::vector<double> to_numbers(const Json& value, std::size_t n, const std::string& path,
                               const std::string& source);

}  // namespace trackphys::json_io
