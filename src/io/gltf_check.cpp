// check_gltf (mesh_checks.hpp): a glTF 2 document's references and sizes: every buffer it
// names (external files only inside the mesh's folder, data: URIs well formed), every buffer
// view and accessor inside what holds it, every index in range, and the node tree a tree of
// bounded depth, accessors of the kinds the geometry needs, node transforms assimp composes
// as glTF means them, and no required extension that would change the geometry unread.
// assimp's glTF 2 reader trusts these (a sparse accessor without an indices view, or a skin
// without its matrices, crashes it; a buffer URI of /etc/passwd or ../ reads that file as a
// mesh).

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <set>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include <nlohmann/json.hpp>

#include "io/mesh_checks.hpp"
#include "trackphys/error.hpp"
#include "trackphys/io/regular_file.hpp"

namespace trackphys::detail {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;

[[noreturn]] void fail(const std::string& place, const std::string& reason) {
    throw MeshCheckError{"glTF " + place + ": " + reason};
}

std::string at(const std::string& array, std::size_t i) {
    return array + "[" + std::to_string(i) + "]";
}

// The array under key (empty when absent).
const Json& array_of(const Json& object, const char* key) {
    static const Json empty = Json::array();
    const auto it = object.find(key);
    if (it == object.end()) return empty;
    if (!it->is_array()) fail(key, "not an array");
    return *it;
}

// A non-negative integer under key, or fallback when absent.
std::uint64_t number_of(const Json& object, const char* key, const std::string& place,
                        std::uint64_t fallback) {
    const auto it = object.find(key);
    if (it == object.end()) return fallback;
    if (!it->is_number_unsigned()) fail(place + "." + key, "not a non-negative integer");
    return it->get<std::uint64_t>();
}

// Fails unless the integer under key (when present) indexes an array of size items.
void check_index(const Json& object, const char* key, const std::string& place, std::size_t size) {
    const auto it = object.find(key);
    if (it == object.end()) return;
    if (!it->is_number_unsigned() || it->get<std::uint64_t>() >= size)
        fail(place + "." + key,
             quoted_text(it->dump()) + " is not an index below " + std::to_string(size));
}

std::uint64_t required(const Json& object, const char* key, const std::string& place) {
    if (!object.contains(key)) fail(place, "no " + std::string(key));
    return number_of(object, key, place, 0);
}

bool is_base64(char ch) {
    return (ch >= 'A' && ch <= 'Z') || (ch >= 'a' && ch <= 'z') || (ch >= '0' && ch <= '9') ||
           ch == '+' || ch == '/';
}

// The byte count of a data: URI's payload; fails unless it is base64 as data:[type];base64,...
std::uint64_t data_uri_bytes(std::string_view uri, const std::string& place) {
    const std::size_t comma = uri.find(',');
    if (comma == std::string_view::npos || uri.substr(0, comma).size() < 12 ||
        uri.substr(comma - 7, 7) != ";base64")
        fail(place, "a malformed data: URI (only data:[type];base64,... is read)");
    const std::string_view payload = uri.substr(comma + 1);
    std::size_t pad = 0;
    while (pad < 2 && pad < payload.size() && payload[payload.size() - 1 - pad] == '=') ++pad;
    if (payload.size() % 4 != 0)
        fail(place, "a data: URI whose base64 length is not a multiple of 4");
    for (std::size_t i = 0; i < payload.size() - pad; ++i)
        if (!is_base64(payload[i])) fail(place, "a data: URI with a character outside base64");
    return payload.size() / 4 * 3 - pad;
}

// A reference to a file beside the mesh, refused when it could leave the mesh's folder or
// name anything but a plain file there.
fs::path local_file(std::string_view uri, const fs::path& folder, const std::string& place) {
    const std::string shown = quoted_text(uri);
    if (uri.empty()) fail(place, "an empty URI");
    if (uri.find(':') != std::string_view::npos)
        fail(place, "the reference " + shown +
                        " is a URL or an absolute path (only files in "
                        "the mesh's folder are read)");
    if (uri[0] == '/' || uri.find('\\') != std::string_view::npos)
        fail(place, "the reference " + shown +
                        " is an absolute path or uses '\\' (only files in "
                        "the mesh's folder are read)");
    if (uri.find('%') != std::string_view::npos)
        fail(place, "the reference " + shown + " is percent-encoded (not read)");
    for (const fs::path& part : fs::path(uri))
        if (part == "..") fail(place, "the reference " + shown + " leaves the mesh's folder");
    const fs::path file = folder / fs::path(uri);
    std::error_code ec;
    if (!fs::is_regular_file(file, ec)) fail(place, "the reference " + shown + " is no file");
    if (!lies_inside(file, folder.empty() ? fs::path(".") : folder))
        fail(place,
             "the reference " + shown + " leads out of the mesh's folder through a symbolic link");
    return file;
}

// glTF's own structure is a few levels deep (a primitive's attributes are at depth 5), its
// node tree lives in flat arrays: JSON nested deeper is no model, only a load on the JSON
// parsers (assimp's recurses once per level). Not MeshLoadLimits::max_nesting, which counts
// nodes.
constexpr int kMaxJsonDepth = 64;

// Parses JSON whose nesting is at most kMaxJsonDepth deep.
Json parse(std::string_view text) {
    const Json::parser_callback_t depth_limit = [](int depth, Json::parse_event_t, Json&) {
        if (depth > kMaxJsonDepth)
            throw MeshCheckError{"glTF JSON nested deeper than " + std::to_string(kMaxJsonDepth)};
        return true;
    };
    try {
        Json doc = Json::parse(text.begin(), text.end(), depth_limit);
        if (!doc.is_object()) throw MeshCheckError{"glTF JSON is not an object"};
        return doc;
    } catch (const Json::exception& e) {
        throw MeshCheckError{std::string("glTF JSON: ") + e.what()};
    }
}

struct Glb {
    std::string_view json;
    bool has_bin = false;
    std::uint64_t bin_bytes = 0;
};

std::uint32_t u32_at(std::string_view bytes, std::size_t at) {
    std::uint32_t v = 0;
    for (std::size_t k = 4; k-- > 0;) v = (v << 8) | static_cast<unsigned char>(bytes[at + k]);
    return v;
}

// The GLB container: a 12-byte header, a JSON chunk, an optional BIN chunk, each inside the file.
Glb split_glb(std::string_view file) {
    if (file.size() < 20 || file.substr(0, 4) != "glTF" || u32_at(file, 4) != 2)
        throw MeshCheckError{"byte 0: not a GLB 2 header"};
    if (u32_at(file, 8) != file.size())
        throw MeshCheckError{"byte 8: the GLB header's length " + std::to_string(u32_at(file, 8)) +
                             " is not the file's " + std::to_string(file.size())};
    Glb glb;
    const std::uint64_t json_bytes = u32_at(file, 12);
    if (file.substr(16, 4) != "JSON" || json_bytes > file.size() - 20)
        throw MeshCheckError{"byte 12: the first GLB chunk is not JSON inside the file"};
    glb.json = file.substr(20, json_bytes);
    const std::size_t next = 20 + static_cast<std::size_t>(json_bytes);
    if (next == file.size()) return glb;
    if (file.size() - next < 8 || file.substr(next + 4, 4) != std::string_view("BIN\0", 4) ||
        u32_at(file, next) > file.size() - next - 8)
        throw MeshCheckError{"byte " + std::to_string(next) +
                             ": the second GLB chunk is not BIN inside the file"};
    glb.has_bin = true;
    glb.bin_bytes = u32_at(file, next);
    return glb;
}

std::uint64_t component_bytes(std::uint64_t type, const std::string& place) {
    switch (type) {
        case 5120:
        case 5121:
            return 1;
        case 5122:
        case 5123:
            return 2;
        case 5125:
        case 5126:
            return 4;
        default:
            fail(place + ".componentType", std::to_string(type) + " is no component type");
    }
}

std::uint64_t components(const Json& accessor, const std::string& place) {
    const auto it = accessor.find("type");
    const std::string type = it != accessor.end() && it->is_string() ? it->get<std::string>() : "";
    if (type == "SCALAR") return 1;
    if (type == "VEC2") return 2;
    if (type == "VEC3") return 3;
    if (type == "VEC4" || type == "MAT2") return 4;
    if (type == "MAT3") return 9;
    if (type == "MAT4") return 16;
    fail(place + ".type", "not an accessor type");
}

class GltfChecker {
  public:
    GltfChecker(const Json& doc, const Glb* glb, const fs::path& folder, std::size_t max_nesting)
        : doc_(doc), glb_(glb), folder_(folder), max_nesting_(max_nesting) {}

    std::set<fs::path> run() {
        const auto asset = doc_.find("asset");
        if (asset == doc_.end() || !asset->is_object() || !asset->contains("version") ||
            !(*asset)["version"].is_string() ||
            (*asset)["version"].get<std::string>().rfind("2.", 0) != 0)
            fail("asset.version", "not glTF 2");
        check_required_extensions();
        check_buffers();
        check_images();
        check_buffer_views();
        check_accessors();
        check_meshes();
        check_nodes();
        check_scenes();
        check_skins_and_animations();
        return files_;
    }

  private:
    // A required extension that stores the geometry otherwise (Draco or meshopt compression)
    // would load as something else, or not at all. Those of materials, textures, lights and
    // quantized attributes (positions must still be float: check_geometry_accessors) leave
    // the triangles alone, and GPU instancing is refused on the node that uses it, saying what
    // to do.
    void check_required_extensions() {
        const Json& required_extensions = array_of(doc_, "extensionsRequired");
        for (std::size_t e = 0; e < required_extensions.size(); ++e) {
            const Json& name = required_extensions[e];
            const std::string text = name.is_string() ? name.get<std::string>() : name.dump();
            if (!(text.starts_with("KHR_materials_") || text.starts_with("KHR_texture_") ||
                  text.starts_with("EXT_texture_") || text == "MSFT_texture_dds" ||
                  text == "KHR_lights_punctual" || text == "KHR_mesh_quantization" ||
                  text == "EXT_mesh_gpu_instancing"))
                fail(at("extensionsRequired", e),
                     quoted_text(text) + " may change the geometry, and it is not read");
        }
    }

    void check_buffers() {
        const Json& buffers = array_of(doc_, "buffers");
        for (std::size_t i = 0; i < buffers.size(); ++i) {
            const std::string place = at("buffers", i);
            const Json& b = buffers[i];
            if (!b.is_object()) fail(place, "not an object");
            const std::uint64_t length = required(b, "byteLength", place);
            std::uint64_t available = 0;
            const auto uri = b.find("uri");
            if (uri == b.end()) {
                if (glb_ == nullptr || i != 0 || !glb_->has_bin)
                    fail(place, "no uri, and no GLB BIN chunk to stand for it");
                available = glb_->bin_bytes;
            } else if (!uri->is_string()) {
                fail(place + ".uri", "not a string");
            } else if (const std::string text = uri->get<std::string>();
                       text.rfind("data:", 0) == 0) {
                available = data_uri_bytes(text, place + ".uri");
            } else {
                const fs::path file = local_file(text, folder_, place + ".uri");
                std::error_code ec;
                available = fs::file_size(file, ec);
                files_.insert(file);
            }
            if (length > available)
                fail(place, "byteLength " + std::to_string(length) + " but only " +
                                std::to_string(available) + " bytes hold it");
            buffer_bytes_.push_back(length);
        }
    }

    // Images are never opened (collision needs none), but assimp decodes data: URIs.
    void check_images() {
        const Json& images = array_of(doc_, "images");
        for (std::size_t i = 0; i < images.size(); ++i) {
            const auto uri = images[i].is_object() ? images[i].find("uri") : images[i].end();
            if (uri != images[i].end() && uri->is_string() &&
                uri->get<std::string>().rfind("data:", 0) == 0)
                data_uri_bytes(uri->get<std::string>(), at("images", i) + ".uri");
        }
    }

    void check_buffer_views() {
        const Json& views = array_of(doc_, "bufferViews");
        for (std::size_t i = 0; i < views.size(); ++i) {
            const std::string place = at("bufferViews", i);
            const Json& v = views[i];
            if (!v.is_object()) fail(place, "not an object");
            const std::uint64_t buffer = required(v, "buffer", place);
            if (buffer >= buffer_bytes_.size()) fail(place + ".buffer", "no such buffer");
            const std::uint64_t offset = number_of(v, "byteOffset", place, 0);
            const std::uint64_t length = required(v, "byteLength", place);
            if (offset > buffer_bytes_[buffer] || length > buffer_bytes_[buffer] - offset)
                fail(place, "bytes " + std::to_string(offset) + " + " + std::to_string(length) +
                                " run past buffer " + std::to_string(buffer) + "'s " +
                                std::to_string(buffer_bytes_[buffer]));
            const std::uint64_t stride = number_of(v, "byteStride", place, 0);
            if (v.contains("byteStride") && (stride < 4 || stride > 252 || stride % 4 != 0))
                fail(place + ".byteStride", std::to_string(stride) + " is not 4 to 252 by 4");
            views_.push_back({length, stride});
        }
    }

    void check_accessors() {
        const Json& accessors = array_of(doc_, "accessors");
        for (std::size_t i = 0; i < accessors.size(); ++i) {
            const std::string place = at("accessors", i);
            const Json& a = accessors[i];
            if (!a.is_object()) fail(place, "not an object");
            if (a.contains("sparse"))
                fail(place, "a sparse accessor (not read: collision geometry needs none)");
            if (!a.contains("bufferView")) fail(place, "no bufferView (not read)");
            check_index(a, "bufferView", place, views_.size());
            const View& view = views_[a["bufferView"].get<std::size_t>()];
            const std::uint64_t element =
                components(a, place) * component_bytes(required(a, "componentType", place), place);
            const std::uint64_t count = required(a, "count", place);
            const std::uint64_t offset = number_of(a, "byteOffset", place, 0);
            const std::uint64_t stride = view.stride != 0 ? view.stride : element;
            if (count == 0 || count > 0xffffffffu) fail(place + ".count", "not 1 to 2^32 - 1");
            if (stride < element)
                fail(place, "elements of " + std::to_string(element) +
                                " bytes overlap in its buffer view's stride of " +
                                std::to_string(stride));
            // count <= 2^32 and stride <= 252: no overflow in 64 bits.
            if (offset > view.bytes || (count - 1) * stride + element > view.bytes - offset)
                fail(place, std::to_string(count) + " elements of " + std::to_string(element) +
                                " bytes every " + std::to_string(stride) + " from byte " +
                                std::to_string(offset) + " run past its buffer view's " +
                                std::to_string(view.bytes) + " bytes");
        }
    }

    // What the importer reads of a primitive: positions as float triples and indices as
    // unsigned integers, in whole triangles when the mode is triangles (the default): it
    // read other kinds as garbage triangles and dropped a last partial triangle unsaid.
    void check_geometry_accessors(const Json& primitive, const Json& attributes,
                                  const std::string& place) {
        const Json& accessors = array_of(doc_, "accessors");
        const auto accessor = [&](const Json& index) -> const Json& {
            return accessors[index.get<std::size_t>()];
        };
        const auto type = [](const Json& a) { return a.value("componentType", std::uint64_t{0}); };
        const auto count = [](const Json& a) { return a.value("count", std::uint64_t{0}); };
        const bool triangles = number_of(primitive, "mode", place, 4) == 4;
        if (const auto position = attributes.find("POSITION"); position != attributes.end()) {
            const Json& a = accessor(*position);
            if (components(a, place) != 3 || type(a) != 5126)
                fail(place + ".attributes.POSITION", "not an accessor of float VEC3");
            if (triangles && !primitive.contains("indices") && count(a) % 3 != 0)
                fail(place, std::to_string(count(a)) +
                                " vertices without indices, not whole "
                                "triangles");
        }
        if (const auto indices = primitive.find("indices"); indices != primitive.end()) {
            const Json& a = accessor(*indices);
            if (components(a, place) != 1 ||
                !(type(a) == 5121 || type(a) == 5123 || type(a) == 5125))
                fail(place + ".indices", "not an accessor of unsigned integers");
            if (triangles && count(a) % 3 != 0)
                fail(place + ".indices",
                     std::to_string(count(a)) + " indices, not whole triangles");
        }
    }

    void check_meshes() {
        const std::size_t accessors = array_of(doc_, "accessors").size();
        const Json& meshes = array_of(doc_, "meshes");
        for (std::size_t m = 0; m < meshes.size(); ++m) {
            if (!meshes[m].is_object()) fail(at("meshes", m), "not an object");
            const Json& primitives = array_of(meshes[m], "primitives");
            for (std::size_t p = 0; p < primitives.size(); ++p) {
                const std::string place = at(at("meshes", m) + ".primitives", p);
                const Json& primitive = primitives[p];
                if (!primitive.is_object()) fail(place, "not an object");
                check_index(primitive, "indices", place, accessors);
                check_index(primitive, "material", place, array_of(doc_, "materials").size());
                if (number_of(primitive, "mode", place, 4) > 6) fail(place + ".mode", "not 0 to 6");
                const auto attributes = primitive.find("attributes");
                if (attributes == primitive.end() || !attributes->is_object())
                    fail(place, "no attributes");
                for (const auto& [name, index] : attributes->items())
                    check_index(*attributes, name.c_str(), place + ".attributes", accessors);
                check_geometry_accessors(primitive, *attributes, place);
                const Json& targets = array_of(primitive, "targets");
                for (std::size_t t = 0; t < targets.size(); ++t) {
                    if (!targets[t].is_object()) fail(at(place + ".targets", t), "not an object");
                    for (const auto& [name, index] : targets[t].items())
                        check_index(targets[t], name.c_str(), at(place + ".targets", t), accessors);
                }
            }
        }
    }

    // A node's own transform as assimp composes it: a rotation that is not a unit quaternion
    // scaled the mesh (a 1 m quad placed 199 m long), a matrix whose last row is not
    // 0, 0, 0, 1 was taken as affine all the same, and GPU instances are not read at all.
    void check_node_transform(const Json& node, const std::string& place) {
        const auto extensions = node.find("extensions");
        if (extensions != node.end() && extensions->is_object() &&
            extensions->contains("EXT_mesh_gpu_instancing"))
            fail(place,
                 "EXT_mesh_gpu_instancing: its instances are not read (export them as "
                 "nodes)");
        const auto numbers = [&](const char* key, std::size_t n) -> std::vector<double> {
            const auto it = node.find(key);
            if (it == node.end()) return {};
            if (!it->is_array() || it->size() != n ||
                !std::all_of(it->begin(), it->end(), [](const Json& x) { return x.is_number(); }))
                fail(place + "." + key, "not " + std::to_string(n) + " numbers");
            std::vector<double> out;
            for (const Json& x : *it) out.push_back(x.get<double>());
            return out;
        };
        if (const std::vector<double> q = numbers("rotation", 4); !q.empty()) {
            const double length2 = q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3];
            // float32 rounding leaves ~1e-7; 1e-3 would stretch a 5 km track by 2.5 m.
            if (!(std::abs(length2 - 1.0) <= 1e-5))
                fail(place + ".rotation", "not a unit quaternion");
        }
        if (const std::vector<double> m = numbers("matrix", 16); !m.empty())
            if (m[3] != 0.0 || m[7] != 0.0 || m[11] != 0.0 || m[15] != 1.0)
                fail(place + ".matrix", "not an affine transform (its last row is not 0, 0, 0, 1)");
    }

    // Nodes form a forest: every child in range, no node a child twice, no cycle, at most
    // max_nesting_ deep (assimp recurses once per level).
    void check_nodes() {
        const Json& nodes = array_of(doc_, "nodes");
        std::vector<bool> has_parent(nodes.size(), false);
        for (std::size_t n = 0; n < nodes.size(); ++n) {
            const std::string place = at("nodes", n);
            if (!nodes[n].is_object()) fail(place, "not an object");
            check_index(nodes[n], "mesh", place, array_of(doc_, "meshes").size());
            check_index(nodes[n], "skin", place, array_of(doc_, "skins").size());
            check_index(nodes[n], "camera", place, array_of(doc_, "cameras").size());
            check_node_transform(nodes[n], place);
            const Json& children = array_of(nodes[n], "children");
            for (std::size_t c = 0; c < children.size(); ++c) {
                if (!children[c].is_number_unsigned() ||
                    children[c].get<std::uint64_t>() >= nodes.size())
                    fail(at(place + ".children", c), "no such node");
                const std::size_t child = children[c].get<std::size_t>();
                if (has_parent[child])
                    fail(at(place + ".children", c),
                         "node " + std::to_string(child) + " has two parents");
                has_parent[child] = true;
            }
        }
        std::vector<std::pair<std::size_t, std::size_t>> pending;  // node, depth
        for (std::size_t n = 0; n < nodes.size(); ++n)
            if (!has_parent[n]) pending.push_back({n, 1});
        std::size_t reached = 0;
        while (!pending.empty()) {
            const auto [n, depth] = pending.back();
            pending.pop_back();
            ++reached;
            if (depth > max_nesting_)
                fail(at("nodes", n), "nested deeper than " + std::to_string(max_nesting_) +
                                         ", the limit max_nesting");
            for (const Json& child : array_of(nodes[n], "children"))
                pending.push_back({child.get<std::size_t>(), depth + 1});
        }
        if (reached != nodes.size()) fail("nodes", "children form a cycle");
    }

    void check_scenes() {
        const std::size_t nodes = array_of(doc_, "nodes").size();
        const Json& scenes = array_of(doc_, "scenes");
        check_index(doc_, "scene", "document", scenes.size());
        for (std::size_t s = 0; s < scenes.size(); ++s) {
            if (!scenes[s].is_object()) fail(at("scenes", s), "not an object");
            const Json& roots = array_of(scenes[s], "nodes");
            for (std::size_t r = 0; r < roots.size(); ++r)
                if (!roots[r].is_number_unsigned() || roots[r].get<std::uint64_t>() >= nodes)
                    fail(at(at("scenes", s) + ".nodes", r), "no such node");
        }
    }

    // Skins and animations are not geometry, but assimp resolves their references. It also
    // reads a skin's inverse bind matrices, one float MAT4 a joint, without looking: a skin
    // without them (glTF allows it: identity matrices) crashed it, one with fewer than its
    // joints made it read past them.
    void check_skins_and_animations() {
        const std::size_t nodes = array_of(doc_, "nodes").size();
        const Json& accessors = array_of(doc_, "accessors");
        const Json& skins = array_of(doc_, "skins");
        for (std::size_t s = 0; s < skins.size(); ++s) {
            const std::string place = at("skins", s);
            if (!skins[s].is_object()) fail(place, "not an object");
            check_index(skins[s], "skeleton", place, nodes);
            const Json& joints = array_of(skins[s], "joints");
            for (std::size_t j = 0; j < joints.size(); ++j)
                if (!joints[j].is_number_unsigned() || joints[j].get<std::uint64_t>() >= nodes)
                    fail(at(place + ".joints", j), "no such node");
            if (!skins[s].contains("inverseBindMatrices"))
                fail(place, "no inverseBindMatrices (not read: the importer needs them)");
            check_index(skins[s], "inverseBindMatrices", place, accessors.size());
            const Json& matrices = accessors[skins[s]["inverseBindMatrices"].get<std::size_t>()];
            if (components(matrices, place) != 16 ||
                matrices.value("componentType", std::uint64_t{0}) != 5126 ||
                matrices.value("count", std::uint64_t{0}) < joints.size())
                fail(place + ".inverseBindMatrices", "not a float MAT4 for each of its " +
                                                         std::to_string(joints.size()) + " joints");
        }
        const std::size_t accessor_count = accessors.size();
        const Json& animations = array_of(doc_, "animations");
        for (std::size_t a = 0; a < animations.size(); ++a) {
            const std::string place = at("animations", a);
            if (!animations[a].is_object()) fail(place, "not an object");
            const Json& samplers = array_of(animations[a], "samplers");
            for (std::size_t s = 0; s < samplers.size(); ++s) {
                if (!samplers[s].is_object()) fail(at(place + ".samplers", s), "not an object");
                check_index(samplers[s], "input", at(place + ".samplers", s), accessor_count);
                check_index(samplers[s], "output", at(place + ".samplers", s), accessor_count);
            }
            const Json& channels = array_of(animations[a], "channels");
            for (std::size_t c = 0; c < channels.size(); ++c) {
                const std::string channel = at(place + ".channels", c);
                if (!channels[c].is_object()) fail(channel, "not an object");
                check_index(channels[c], "sampler", channel, samplers.size());
                const auto target = channels[c].find("target");
                if (target != channels[c].end() && target->is_object())
                    check_index(*target, "node", channel + ".target", nodes);
            }
        }
    }

    struct View {
        std::uint64_t bytes;
        std::uint64_t stride;  // 0: tightly packed
    };

    const Json& doc_;
    const Glb* glb_;
    const fs::path& folder_;
    const std::size_t max_nesting_;
    std::vector<std::uint64_t> buffer_bytes_;
    std::vector<View> views_;
    std::set<fs::path> files_;
};

}  // namespace

std::set<fs::path> check_gltf(std::string_view file, bool binary, const fs::path& folder,
                              std::size_t max_nesting) {
    if (!binary) return GltfChecker(parse(file), nullptr, folder, max_nesting).run();
    const Glb glb = split_glb(file);
    return GltfChecker(parse(glb.json), &glb, folder, max_nesting).run();
}

}  // namespace trackphys::detail
