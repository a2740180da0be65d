#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <limits>
#include <memory>
#include <new>
#include <set>
#include <string>
#include <string_view>
#include <system_error>
#include <utility>
#include <vector>

#include <assimp/BaseImporter.h>
#include <assimp/config.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <assimp/Importer.hpp>
#include <glm/mat4x4.hpp>
#include <glm/matrix.hpp>

#include "io/confined_io_system.hpp"
#include "io/file_bytes.hpp"
#include "io/first_of_each_key.hpp"
#include "io/mesh_checks.hpp"
#include "io/mesh_format.hpp"
#include "trackphys/error.hpp"
#include "trackphys/geometry/triangle.hpp"
#include "trackphys/io/mesh_io.hpp"
#include "trackphys/io/mesh_load_limits.hpp"
#include "trackphys/math/types.hpp"

namespace trackphys {
namespace {

namespace fs = std::filesystem;

[[noreturn]] void fail(const fs::path& path, const std::string& reason) {
    throw Error("mesh file '" + path.string() + "': " + reason);
}

std::string format_point(const glm::dvec3& p) {
    char text[96];
    std::snprintf(text, sizeof text, "(%.9g, %.9g, %.9g)", p.x, p.y, p.z);
    return text;
}

std::string mesh_label(const aiMesh& mesh, unsigned index) {
    if (mesh.mName.length > 0) return "mesh " + quoted_text({mesh.mName.data, mesh.mName.length});
    return "mesh #" + std::to_string(index);
}

std::string node_label(const aiNode& node) {
    return "node " + quoted_text({node.mName.data, node.mName.length});
}

// assimp answers a missing or empty file with messages that depend on the format it guesses
// from the extension ("OBJ-file is too small"); these checks give the plain reason first.
void check_is_nonempty_file(const fs::path& path) {
    std::error_code ec;
    const fs::file_status status = fs::status(path, ec);
    if (status.type() == fs::file_type::not_found) fail(path, "no such file");
    if (ec) fail(path, "cannot access it: " + ec.message());
    if (!fs::is_regular_file(status)) fail(path, "not a regular file");
    const std::uintmax_t size = fs::file_size(path, ec);
    if (ec) fail(path, "cannot read its size: " + ec.message());
    if (size == 0) fail(path, "the file is empty");
}

detail::MeshFormat format_of(const fs::path& path) {
    if (const auto format = detail::mesh_format_of(path)) return *format;
    fail(path, "not a mesh format trackphys reads (it reads " + detail::read_mesh_extensions() +
                   "; other formats' readers in assimp cannot be bounded against hostile files)");
}

// A limit of zero would refuse every file, and nesting beyond max_mesh_nesting_allowed could
// exhaust the stack in assimp's recursive readers: both are the caller's mistake.
void check_limits(const MeshLoadLimits& limits) {
    const auto refuse = [](const char* name, const std::string& why) {
        throw Error(std::string("MeshLoadLimits::") + name + " " + why);
    };
    if (limits.max_triangles == 0) refuse("max_triangles", "is 0: no mesh would load");
    if (limits.max_vertices == 0) refuse("max_vertices", "is 0: no mesh would load");
    if (limits.max_bytes == 0) refuse("max_bytes", "is 0: no mesh would load");
    if (limits.max_polygon_corners < 3)
        refuse("max_polygon_corners",
               "is " + std::to_string(limits.max_polygon_corners) + ": no triangle would load");
    if (limits.max_nesting == 0) refuse("max_nesting", "is 0: no mesh would load");
    if (limits.max_nesting > max_mesh_nesting_allowed)
        refuse("max_nesting", "is " + std::to_string(limits.max_nesting) + ", more than the " +
                                  std::to_string(max_mesh_nesting_allowed) +
                                  " assimp's recursive readers are safe at");
}

void check_byte_limit(const fs::path& path, std::uintmax_t bytes, const MeshLoadLimits& limits,
                      const char* what) {
    if (bytes > limits.max_bytes)
        fail(path, std::string(what) + " " + std::to_string(bytes) + " bytes, more than " +
                       std::to_string(limits.max_bytes) + ", the limit max_bytes");
}

// Unregisters every assimp reader but the format's own, so that assimp never hands the file
// to another one by guessing from its content (it does when the extension's reader declines
// the file). Unregistered readers are the caller's to delete: the importer no longer owns them.
std::vector<std::unique_ptr<Assimp::BaseImporter>> keep_only_reader(Assimp::Importer& importer,
                                                                    detail::MeshFormat format) {
    const std::string kept = detail::assimp_reader_name(format);
    std::vector<std::unique_ptr<Assimp::BaseImporter>> removed;
    for (std::size_t i = importer.GetImporterCount(); i-- > 0;) {
        Assimp::BaseImporter* reader = importer.GetImporter(i);
        if (kept == reader->GetInfo()->mName) continue;
        importer.UnregisterLoader(reader);
        removed.emplace_back(reader);
    }
    return removed;
}

// assimp's triangulation trusts each mesh's mPrimitiveTypes: a mesh that claims polygons but
// holds none fails an ai_assert that Debian's assimp 5.2.5 keeps on, and it aborts the whole
// process (found by fuzz_mesh_import: a mangled ASCII PLY whose reader made faces of no
// index and flagged the mesh polygonal). The validation pass checks neither, so faces of no
// index are rejected (inspect_before_triangulation) and the claim is recomputed from the faces.
void set_primitive_types_from_faces(aiScene& scene) {
    for (unsigned m = 0; m < scene.mNumMeshes; ++m) {
        aiMesh& mesh = *scene.mMeshes[m];
        unsigned types = 0;
        for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
            const unsigned n = mesh.mFaces[f].mNumIndices;
            const aiPrimitiveType type = n == 1   ? aiPrimitiveType_POINT
                                         : n == 2 ? aiPrimitiveType_LINE
                                         : n == 3 ? aiPrimitiveType_TRIANGLE
                                                  : aiPrimitiveType_POLYGON;
            types |= static_cast<unsigned>(type);
        }
        mesh.mPrimitiveTypes = types;
    }
}

// assimp reads coordinates as floats, so a file's 1e39 or 1e308 arrives as inf, as an "inf"
// does: said, so that a message about "inf" is not taken to misread a finite number.
std::string beyond_single_precision_note(const glm::dvec3& p) {
    if (!(std::isinf(p.x) || std::isinf(p.y) || std::isinf(p.z))) return {};
    return " (assimp reads coordinates in single precision: inf there is an infinite number in "
           "the file or one beyond +-3.4e38)";
}

// aiMatrix4x4 is row-major (a4, b4, c4 hold the translation); glm is column-major.
glm::dmat4 to_dmat4(const aiMatrix4x4& m) {
    glm::dmat4 out(1.0);
    for (unsigned row = 0; row < 4; ++row)
        for (unsigned col = 0; col < 4; ++col) out[col][row] = static_cast<double>(m[row][col]);
    return out;
}

bool is_finite(const glm::dmat4& m) {
    for (int col = 0; col < 4; ++col)
        for (int row = 0; row < 4; ++row)
            if (!std::isfinite(m[col][row])) return false;
    return true;
}

// Mixes three 64-bit words into a hash in which every input bit moves every output bit (for
// FirstOfEachKey). Each word is folded in by a multiply, which carries a bit only upwards,
// so MurmurHash3's 64-bit finaliser ends it: without it the sign and exponent bits of z
// reached no slot bit, and (x, y, z) and (x, y, -z) probed from one slot.
std::uint64_t mixed(std::uint64_t a, std::uint64_t b, std::uint64_t c) {
    std::uint64_t h = a * 0x9E3779B97F4A7C15ull;
    h = (h ^ (h >> 31) ^ b) * 0xC2B2AE3D27D4EB4Full;
    h = (h ^ (h >> 29) ^ c) * 0x165667B19E3779F9ull;
    h = (h ^ (h >> 33)) * 0xFF51AFD7ED558CCDull;
    h = (h ^ (h >> 33)) * 0xC4CEB9FE1A85EC53ull;
    return h ^ (h >> 33);
}

// A vertex is keyed by its position's bits (+0 stored for -0, so the two weld).
struct PositionKey {
    const glm::dvec3& operator()(const glm::dvec3& p) const { return p; }
    std::uint64_t hash(const glm::dvec3& p) const {
        return mixed(std::bit_cast<std::uint64_t>(p.x), std::bit_cast<std::uint64_t>(p.y),
                     std::bit_cast<std::uint64_t>(p.z));
    }
};

// A triangle is keyed by its corners in ascending order: the same in any order or winding.
struct CornerSetKey {
    using Corners = std::array<std::uint32_t, 3>;
    Corners operator()(const Corners& c) const {
        const std::uint32_t lo = std::min(c[0], c[1]), hi = std::max(c[0], c[1]);
        return {std::min(lo, c[2]), std::max(lo, std::min(hi, c[2])), std::max(hi, c[2])};
    }
    std::uint64_t hash(const Corners& s) const { return mixed(s[0], s[1], s[2]); }
};

// Welds vertices whose world positions are bit-identical (+0 and -0 taken as equal), so
// that a format which stores one vertex per face corner (OBJ through assimp, STL) still
// gives a connected mesh. Exact equality only: welding near-equal points would move
// geometry. Indices are handed out in first-use order, so the result is deterministic.
class VertexWelder {
  public:
    explicit VertexWelder(std::vector<glm::dvec3>& vertices)
        : vertices_(vertices), first_(vertices) {}

    /// The index of p in vertices, appending it on first use; false when the index would
    /// not fit the mesh's 32-bit indices.
    bool index_of(const glm::dvec3& p, std::uint32_t& index) {
        if (vertices_.size() >= std::numeric_limits<std::uint32_t>::max()) return false;
        vertices_.emplace_back(p.x + 0.0, p.y + 0.0, p.z + 0.0);  // -0.0 + 0.0 = +0.0
        const std::size_t last = vertices_.size() - 1;
        const std::size_t first = first_.first_of(last);
        if (first != last) vertices_.pop_back();
        index = static_cast<std::uint32_t>(first);
        return true;
    }

  private:
    std::vector<glm::dvec3>& vertices_;
    detail::FirstOfEachKey<glm::dvec3, PositionKey> first_;
};

// Everything about one file's import: the scene is read in two passes (validation before
// triangulation, so that a NaN is reported against the file's own vertex numbering, and
// merging after it).
class SceneMerger {
  public:
    SceneMerger(const fs::path& path, MeshLoadReport& report, const MeshLoadLimits& limits)
        : path_(path),
          report_(report),
          limits_(limits),
          welder_(mesh_.vertices),
          first_triangles_(mesh_.triangles) {}

    // Checks every vertex coordinate and counts, per mesh, the triangles its faces should
    // give once triangulated (n - 2 for an n-gon).
    void inspect_before_triangulation(const aiScene& scene) {
        expected_triangles_.assign(scene.mNumMeshes, 0);
        if (scene.mNumMaterials > max_surfaces)
            fail(path_, std::to_string(scene.mNumMaterials) + " materials, more than the " +
                            std::to_string(max_surfaces) + " surface ids");
        // Up to the last material a mesh uses: assimp's glTF importer appends a default one
        // for meshes without a material, which would list a surface of no triangles.
        unsigned used = 0;
        for (unsigned m = 0; m < scene.mNumMeshes; ++m)
            used =
                std::max(used, std::min(scene.mMeshes[m]->mMaterialIndex + 1, scene.mNumMaterials));
        report_.materials.clear();
        for (unsigned k = 0; k < used; ++k) {
            aiString name;
            scene.mMaterials[k]->Get(AI_MATKEY_NAME, name);
            report_.materials.emplace_back(name.C_Str());
        }
        for (unsigned m = 0; m < scene.mNumMeshes; ++m) {
            const aiMesh& mesh = *scene.mMeshes[m];
            if (mesh.mMaterialIndex >= scene.mNumMaterials && scene.mNumMaterials != 0)
                fail(path_, mesh_label(mesh, m) + " refers to missing material #" +
                                std::to_string(mesh.mMaterialIndex));
            for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
                const aiVector3D& p = mesh.mVertices[v];
                const glm::dvec3 q(p.x, p.y, p.z);
                if (!trackphys::is_finite(q))
                    fail(path_, mesh_label(mesh, m) + ", vertex " + std::to_string(v) +
                                    " has a non-finite coordinate " + format_point(q) +
                                    beyond_single_precision_note(q));
            }
            for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
                const unsigned n = mesh.mFaces[f].mNumIndices;
                if (n == 0)
                    fail(path_,
                         mesh_label(mesh, m) + ", face " + std::to_string(f) + " has no indices");
                if (n > limits_.max_polygon_corners)
                    fail(path_, mesh_label(mesh, m) + ", face " + std::to_string(f) + " has " +
                                    std::to_string(n) + " corners, more than " +
                                    std::to_string(limits_.max_polygon_corners) +
                                    ", the limit max_polygon_corners (triangulating a polygon "
                                    "takes time growing with the square of its corners)");
                if (n >= 3) expected_triangles_[m] += n - 2;
            }
        }
    }

    // The triangles the nodes place, counted as triangulation will give them, degenerate ones
    // included (they are dropped later). Refuses a file that places more than
    // limits.max_triangles before any is placed: a 1 MB glTF placing one 10k-triangle mesh by
    // 20,000 nodes took 2.5 minutes and 3.8 GB to fail on the way.
    std::uint64_t placed_triangles(const aiScene& scene) const {
        std::uint64_t placed = 0;
        std::vector<const aiNode*> stack;
        if (scene.mRootNode != nullptr) stack.push_back(scene.mRootNode);
        while (!stack.empty()) {
            const aiNode& node = *stack.back();
            stack.pop_back();
            for (unsigned i = 0; i < node.mNumMeshes; ++i)
                if (node.mMeshes[i] < expected_triangles_.size())
                    placed += expected_triangles_[node.mMeshes[i]];
            if (placed > limits_.max_triangles)
                fail(path_, "more than " + std::to_string(limits_.max_triangles) +
                                (limits_.max_triangles == 1 ? " triangle" : " triangles") +
                                ", the limit max_triangles");
            for (unsigned c = 0; c < node.mNumChildren; ++c) stack.push_back(node.mChildren[c]);
        }
        return placed;
    }

    // Walks the node tree depth-first (iteratively: a hostile file can nest deeply) and
    // merges every mesh each node places.
    // progress hears of the triangles placed (load_mesh's MeshLoadProgress).
    TriangleMesh merge(const aiScene& scene, const MeshLoadProgress& progress) {
        const std::uint64_t placed = placed_triangles(scene);
        // Room for the triangles placed, up to 4M: a file whose placed triangles turn out
        // degenerate costs at most that table (64 MB) for them.
        first_triangles_.reserve(std::min<std::uint64_t>(placed, 1u << 22));
        progress_ = progress;
        placed_total_ = placed;
        if (progress_) progress_(0, placed_total_);
        struct Pending {
            const aiNode* node;
            glm::dmat4 parent_to_world;
        };
        std::vector<Pending> stack;
        if (scene.mRootNode != nullptr) stack.push_back({scene.mRootNode, glm::dmat4(1.0)});
        while (!stack.empty()) {
            const Pending item = stack.back();
            stack.pop_back();
            const aiNode& node = *item.node;
            const glm::dmat4 local = to_dmat4(node.mTransformation);
            if (!is_finite(local)) fail(path_, node_label(node) + " has a non-finite transform");
            const glm::dmat4 world = item.parent_to_world * local;
            for (unsigned i = 0; i < node.mNumMeshes; ++i) {
                const unsigned m = node.mMeshes[i];
                if (m >= scene.mNumMeshes)
                    fail(path_, node_label(node) + " refers to missing mesh #" + std::to_string(m));
                add_instance(*scene.mMeshes[m], m, world, node);
            }
            // Children in reverse so that they pop in file order: deterministic output.
            for (unsigned c = node.mNumChildren; c-- > 0;)
                stack.push_back({node.mChildren[c], world});
        }
        if (progress_ && placed_total_ > 0) progress_(placed_total_, placed_total_);
        report_.triangles = mesh_.triangles.size();
        report_.vertices = mesh_.vertices.size();
        return std::move(mesh_);
    }

  private:
    void add_instance(const aiMesh& mesh, unsigned m, const glm::dmat4& to_world,
                      const aiNode& node) {
        ++report_.mesh_instances;
        // A mirroring transform turns counter-clockwise triangles clockwise; swapping two
        // corners restores the winding, so normals still face the side the file meant.
        const bool mirrored = glm::determinant(glm::dmat3(to_world)) < 0.0;
        if (mirrored) ++report_.mirrored_instances;

        world_.resize(mesh.mNumVertices);
        for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
            const aiVector3D& p = mesh.mVertices[v];
            world_[v] = glm::dvec3(to_world * glm::dvec4(p.x, p.y, p.z, 1.0));
        }

        // A triangle's surface is its mesh's material index (checked against the materials).
        const auto surface =
            report_.materials.empty() ? SurfaceId{0} : static_cast<SurfaceId>(mesh.mMaterialIndex);
        std::size_t triangles_found = 0;
        for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
            const aiFace& face = mesh.mFaces[f];
            if (face.mNumIndices == 1) {
                ++report_.points_skipped;
                continue;
            }
            if (face.mNumIndices == 2) {
                ++report_.lines_skipped;
                continue;
            }
            if (face.mNumIndices != 3)
                fail(path_, mesh_label(mesh, m) + ", face " + std::to_string(f) + " has " +
                                std::to_string(face.mNumIndices) + " indices after triangulation");
            ++triangles_found;
            if (++placed_done_ % kProgressEvery == 0 && placed_done_ < placed_total_ && progress_)
                progress_(placed_done_, placed_total_);
            std::array<unsigned, 3> corner{face.mIndices[0], face.mIndices[1], face.mIndices[2]};
            if (mirrored) std::swap(corner[1], corner[2]);
            for (const unsigned v : corner) {
                if (v >= mesh.mNumVertices)
                    fail(path_, mesh_label(mesh, m) + ", face " + std::to_string(f) +
                                    " refers to missing vertex " + std::to_string(v));
                if (!trackphys::is_finite(world_[v]))
                    fail(path_, mesh_label(mesh, m) + ", vertex " + std::to_string(v) +
                                    " is non-finite once placed by " + node_label(node));
            }
            const Triangle triangle(world_[corner[0]], world_[corner[1]], world_[corner[2]]);
            if (triangle.is_degenerate()) {
                ++report_.degenerate_dropped;
                continue;
            }
            std::array<std::uint32_t, 3> indices{};
            for (std::size_t k = 0; k < 3; ++k)
                if (!welder_.index_of(world_[corner[k]], indices[k]))
                    fail(path_, "more than 2^32 - 2 vertices");
            // Checked as the mesh grows, so that it never holds more than the caller allowed
            // (a glTF can place one mesh many times: the file's size does not bound this).
            if (mesh_.vertices.size() > limits_.max_vertices)
                fail(path_, "more than " + std::to_string(limits_.max_vertices) +
                                (limits_.max_vertices == 1 ? " vertex" : " vertices") +
                                ", the limit max_vertices");
            if (mesh_.triangles.size() == std::numeric_limits<std::uint32_t>::max() - 1)
                fail(path_, "more than 2^32 - 2 triangles");
            mesh_.triangles.push_back(indices);
            // A duplicate's corners are the first's, so it welded no new vertex either.
            const std::size_t last = mesh_.triangles.size() - 1;
            if (first_triangles_.first_of(last) != last) {
                mesh_.triangles.pop_back();
                ++report_.duplicates_dropped;
                continue;
            }
            mesh_.surfaces.push_back(surface);
            report_.bounds.expand(triangle.bounds());
            report_.area += triangle.area();
        }
        if (triangles_found < expected_triangles_[m])
            report_.triangulation_lost += expected_triangles_[m] - triangles_found;
    }

    static constexpr std::size_t kProgressEvery = 65536;  // triangles between reports

    const fs::path& path_;
    MeshLoadReport& report_;
    const MeshLoadLimits& limits_;
    TriangleMesh mesh_;
    VertexWelder welder_;
    detail::FirstOfEachKey<std::array<std::uint32_t, 3>, CornerSetKey> first_triangles_;
    std::vector<std::size_t> expected_triangles_;
    std::vector<glm::dvec3> world_;  // scratch: the current instance's vertices in world space
    MeshLoadProgress progress_;
    std::size_t placed_total_ = 0;
    std::size_t placed_done_ = 0;
};

}  // namespace

TriangleMesh load_mesh(const fs::path& path, MeshLoadReport& report, const MeshLoadLimits& limits,
                       const MeshLoadProgress& progress) {
    report = MeshLoadReport{};
    check_limits(limits);
    check_is_nonempty_file(path);
    const detail::MeshFormat format = format_of(path);
    // Read once: the check walks these bytes and assimp reads them (confined_io_system.hpp).
    // The byte limit is checked on the size of the file opened, before it is read.
    const detail::FileBytes file(path, "mesh file", [&](std::uintmax_t size) {
        check_byte_limit(path, size, limits, "the file is");
    });
    // What the check and assimp read: an OBJ without the UTF-8 byte order mark some editors
    // write first, which made assimp's reader lose the first statement.
    std::string_view bytes = file.bytes();
    if (format == detail::MeshFormat::obj && bytes.starts_with("\xEF\xBB\xBF"))
        bytes.remove_prefix(3);
    std::set<fs::path> buffers;
    try {
        buffers = detail::check_mesh(bytes, format, path.parent_path(), limits.max_nesting);
    } catch (const detail::MeshCheckError& e) {
        fail(path, e.reason);
    }
    std::uintmax_t with_buffers = file.bytes().size();
    for (const fs::path& buffer : buffers) {
        std::error_code ec;
        with_buffers += fs::file_size(buffer, ec);
        if (ec) fail(path, "cannot read the size of its buffer '" + buffer.string() + "'");
    }
    check_byte_limit(path, with_buffers, limits, "with the buffers it names, it is");

    Assimp::Importer importer;
    const auto unused_readers = keep_only_reader(importer, format);
    // The importer owns the IO system.
    importer.SetIOHandler(new detail::ConfinedIoSystem(path, bytes, buffers));
    // Some importers invent a mesh to visualise a skeleton when a file has bones but no
    // mesh; that would be phantom collision geometry.
    importer.SetPropertyBool(AI_CONFIG_IMPORT_NO_SKELETON_MESHES, true);

    // Deliberately few post-processing steps. aiProcess_FindDegenerates and
    // aiProcess_FindInvalidData would drop or patch bad data before we can count or report
    // it; aiProcess_PreTransformVertices would apply the node transforms in float; and
    // aiProcess_JoinIdenticalVertices compares normals and UVs too, so VertexWelder welds
    // by position instead. Triangulation runs as a second pass, after the validation below.
    SceneMerger merger(path, report, limits);
    // What progress throws comes out as it was: the handlers below word the reader's own.
    bool progress_threw = false;
    const MeshLoadProgress heard = [&](std::size_t done, std::size_t total) {
        try {
            progress(done, total);
        } catch (...) {
            progress_threw = true;
            throw;
        }
    };
    try {
        const aiScene* scene = importer.ReadFile(path.string(), aiProcess_ValidateDataStructure);
        // assimp's own words ("OBJ-file is too small.", "An unknown error occurred during
        // converting"), said to come from the reader: they may not name what is wrong.
        if (scene == nullptr)
            fail(path, std::string("assimp cannot read it: ") + importer.GetErrorString());
        merger.inspect_before_triangulation(*scene);
        // The importer owns the scene and hands it out const; it is ours to fix until the
        // next call (the scene itself was never const).
        set_primitive_types_from_faces(const_cast<aiScene&>(*scene));
        scene = importer.ApplyPostProcessing(aiProcess_Triangulate);
        if (scene == nullptr)
            fail(path, std::string("assimp cannot triangulate it: ") + importer.GetErrorString());
        TriangleMesh mesh = merger.merge(*scene, progress ? heard : MeshLoadProgress{});
        if (mesh.triangles.empty())
            fail(path, "contains no triangles (" + std::to_string(report.degenerate_dropped) +
                           " degenerate dropped, " + std::to_string(report.points_skipped) +
                           " points and " + std::to_string(report.lines_skipped) +
                           " lines skipped)");
        return mesh;
    } catch (const Error&) {
        throw;
    } catch (const std::bad_alloc&) {
        if (progress_threw) throw;
        fail(path,
             "out of memory while reading it (MeshLoadLimits' max_triangles and "
             "max_vertices, the CLI's --max-triangles and --max-vertices, bound what a "
             "file may hold)");
    } catch (const std::exception& e) {
        // assimp is built to catch its own exceptions, but an allocation failure on a
        // corrupt size field can still escape; it is bad input like any other.
        if (progress_threw) throw;
        fail(path, std::string("import failed: ") + e.what());
    }
}

TriangleMesh load_mesh(const fs::path& path, const MeshLoadLimits& limits) {
    MeshLoadReport report;
    return load_mesh(path, report, limits);
}

}  // namespace trackphys
