#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <exception>
#include <limits>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include <assimp/material.h>
#include <assimp/scene.h>

#include <assimp/Exporter.hpp>

#include "trackphys/error.hpp"
#include "trackphys/io/mesh_io.hpp"
#include "trackphys/math/types.hpp"

namespace trackphys {
namespace {

namespace fs = std::filesystem;

[[noreturn]] void fail_to_save(const fs::path& path, const std::string& reason) {
    throw Error("cannot save mesh to '" + path.string() + "': " + reason);
}

// Extension (lower case) -> assimp exporter id, nullptr for none. OBJ goes through
// "objnomtl": the plain "obj" exporter also writes a .mtl file that only names assimp's
// default material.
const char* find_exporter_id(const fs::path& path) {
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (ext == ".glb") return "glb2";
    if (ext == ".gltf") return "gltf2";
    if (ext == ".obj") return "objnomtl";
    if (ext == ".ply") return "plyb";
    if (ext == ".stl") return "stlb";
    return nullptr;
}

const char* exporter_id(const fs::path& path) {
    if (const char* id = find_exporter_id(path)) return id;
    fail_to_save(path, "unknown extension '" + path.extension().string() + "' (expected " +
                           std::string(saved_mesh_extensions) + ")");
}

// Rejects what no format can hold, before any file is created.
void validate(const TriangleMesh& mesh, const fs::path& path) {
    if (mesh.triangles.empty()) fail_to_save(path, "the mesh has no triangles");
    if (mesh.vertices.size() > std::numeric_limits<unsigned>::max())
        fail_to_save(path, "more vertices than assimp's 32-bit indices address");
    constexpr double float_max = std::numeric_limits<float>::max();
    for (std::size_t v = 0; v < mesh.vertices.size(); ++v) {
        const glm::dvec3& p = mesh.vertices[v];
        if (!is_finite(p)) fail_to_save(path, "vertex " + std::to_string(v) + " is not finite");
        if (std::abs(p.x) > float_max || std::abs(p.y) > float_max || std::abs(p.z) > float_max)
            fail_to_save(path, "vertex " + std::to_string(v) + " lies beyond float32 range");
    }
    if (!mesh.surfaces.empty() && mesh.surfaces.size() != mesh.triangles.size())
        fail_to_save(path, std::to_string(mesh.surfaces.size()) + " surface ids for " +
                               std::to_string(mesh.triangles.size()) + " triangles");
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
        for (const std::uint32_t i : mesh.triangles[t])
            if (i >= mesh.vertices.size())
                fail_to_save(path, "triangle " + std::to_string(t) + " refers to missing vertex " +
                                       std::to_string(i));
}

// An aiMesh of the given triangles of the mesh with the vertices they use, renumbered in
// order of first use through `renumbered` (one entry per mesh vertex, ~0u, and left so);
// all the vertices, unrenumbered, when it takes every triangle.
aiMesh* make_mesh(const TriangleMesh& mesh, const std::string& name, unsigned material,
                  std::span<const std::uint32_t> triangles,
                  std::vector<std::uint32_t>& renumbered) {
    const bool whole = triangles.size() == mesh.triangles.size();
    std::vector<std::uint32_t> used;  // new vertex -> mesh vertex
    if (whole) {
        used.resize(mesh.vertices.size());
        for (std::uint32_t v = 0; v < used.size(); ++v) renumbered[v] = used[v] = v;
    } else {
        for (const std::uint32_t t : triangles)
            for (const std::uint32_t v : mesh.triangles[t])
                if (renumbered[v] == ~0u) {
                    renumbered[v] = static_cast<std::uint32_t>(used.size());
                    used.push_back(v);
                }
    }
    auto out = std::make_unique<aiMesh>();
    out->mName = aiString(name);
    out->mMaterialIndex = material;
    out->mPrimitiveTypes = aiPrimitiveType_TRIANGLE;
    out->mNumVertices = static_cast<unsigned>(used.size());
    out->mVertices = new aiVector3D[used.size()];
    for (std::size_t v = 0; v < used.size(); ++v) {
        const glm::dvec3& p = mesh.vertices[used[v]];
        // Nearest float32: the only precision assimp's formats hold (see mesh_io.hpp).
        out->mVertices[v] =
            aiVector3D(static_cast<float>(p.x), static_cast<float>(p.y), static_cast<float>(p.z));
    }
    out->mNumFaces = static_cast<unsigned>(triangles.size());
    out->mFaces = new aiFace[triangles.size()];
    for (std::size_t f = 0; f < triangles.size(); ++f) {
        const std::array<std::uint32_t, 3>& t = mesh.triangles[triangles[f]];
        aiFace& face = out->mFaces[f];
        face.mNumIndices = 3;
        face.mIndices = new unsigned[3]{renumbered[t[0]], renumbered[t[1]], renumbered[t[2]]};
    }
    for (const std::uint32_t v : used) renumbered[v] = ~0u;
    return out.release();
}

// The highest surface id of a mesh whose ids 0 to it all have triangles, else 0: glTF keeps
// only the materials its meshes use, so an id without triangles would shift those above it.
SurfaceId highest_of_contiguous_surfaces(const TriangleMesh& mesh) {
    SurfaceId highest = 0;
    for (const SurfaceId id : mesh.surfaces) highest = std::max(highest, id);
    std::vector<bool> present(std::size_t(highest) + 1, false);
    for (const SurfaceId id : mesh.surfaces) present[id] = true;
    return std::find(present.begin(), present.end(), false) == present.end() ? highest : 0;
}

// One node holding the mesh with one default material: the smallest scene every assimp
// exporter accepts (the glTF and OBJ exporters index mMaterials unconditionally). With
// `by_surface` and a mesh whose surface ids 0 to the highest all have triangles, one
// material per id ("surface 0", "surface 1", ...) and one mesh of its triangles, so that a
// glTF file read back gives each triangle its id again (its material's index). aiScene's
// destructor frees everything reachable from it (hence the raw new[]), up to its counts,
// which grow as each part is made: an allocation that fails leaks nothing.
std::unique_ptr<aiScene> make_scene(const TriangleMesh& mesh, const std::string& name,
                                    bool by_surface) {
    const SurfaceId highest = by_surface ? highest_of_contiguous_surfaces(mesh) : SurfaceId{0};
    const unsigned parts = unsigned(highest) + 1;  // meshes and materials
    // Each id's triangles in mesh order, one after the other (a counting sort by id).
    std::vector<std::uint32_t> by_id(mesh.triangles.size());
    std::vector<std::size_t> first(std::size_t(parts) + 1, 0);
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
        ++first[std::size_t(highest == 0 ? 0 : mesh.surfaces[t]) + 1];
    for (unsigned id = 0; id < parts; ++id) first[id + 1] += first[id];
    std::vector<std::size_t> next(first.begin(), first.end() - 1);
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
        by_id[next[highest == 0 ? 0 : mesh.surfaces[t]]++] = static_cast<std::uint32_t>(t);

    auto scene = std::make_unique<aiScene>();
    scene->mRootNode = new aiNode(name);
    scene->mRootNode->mMeshes = new unsigned[parts];
    scene->mMeshes = new aiMesh*[parts];
    scene->mMaterials = new aiMaterial*[parts];
    std::vector<std::uint32_t> renumbered(mesh.vertices.size(), ~0u);
    for (unsigned id = 0; id < parts; ++id) {
        const std::span<const std::uint32_t> triangles(by_id.data() + first[id],
                                                       first[id + 1] - first[id]);
        scene->mMeshes[id] =
            make_mesh(mesh, highest == 0 ? name : name + " surface " + std::to_string(id), id,
                      triangles, renumbered);
        scene->mRootNode->mMeshes[id] = id;
        scene->mNumMeshes = scene->mRootNode->mNumMeshes = id + 1;
        scene->mMaterials[id] = new aiMaterial();
        scene->mNumMaterials = id + 1;
        if (highest == 0) continue;
        const aiString material_name("surface " + std::to_string(id));
        scene->mMaterials[id]->AddProperty(&material_name, AI_MATKEY_NAME);
    }
    return scene;
}

// A fresh folder beside the destination (same file system, so rename is atomic) that the
// exporter writes into under the destination's own file name, so that companion files
// (the .bin of a .gltf) carry the names the main file refers to. commit() renames them into
// place, companions first; anything not committed is removed with the folder.
class StagingFolder {
  public:
    explicit StagingFolder(const fs::path& destination) : destination_(destination) {
        const fs::path parent = destination.has_parent_path() ? destination.parent_path() : ".";
        // Appended piecewise: GCC 12 warns falsely (-Wrestrict) on "." + std::string.
        std::string name = ".";
        name += destination.filename().string();
        name += ".tmp-XXXXXX";
        std::string pattern = (parent / name).string();
        if (::mkdtemp(pattern.data()) == nullptr)
            fail_to_save(destination, "cannot create a temporary folder in '" + parent.string() +
                                          "': " + std::generic_category().message(errno));
        folder_ = pattern;
    }
    StagingFolder(const StagingFolder&) = delete;
    StagingFolder& operator=(const StagingFolder&) = delete;
    ~StagingFolder() {
        std::error_code ignored;
        fs::remove_all(folder_, ignored);
    }

    /// Where the exporter writes the main file.
    fs::path staged_file() const { return folder_ / destination_.filename(); }

    void commit() {
        const fs::path parent = destination_.parent_path();
        std::vector<fs::path> companions;
        for (const fs::directory_entry& entry : fs::directory_iterator(folder_))
            if (entry.path().filename() != destination_.filename())
                companions.push_back(entry.path().filename());
        std::sort(companions.begin(), companions.end());
        std::vector<fs::path> moved;
        try {
            for (const fs::path& name : companions) {
                fs::rename(folder_ / name, parent / name);
                moved.push_back(parent / name);
            }
            fs::rename(staged_file(), destination_);
        } catch (const fs::filesystem_error& e) {
            std::error_code ignored;
            for (const fs::path& p : moved) fs::remove(p, ignored);
            fail_to_save(destination_,
                         "cannot move the written file into place: " + e.code().message());
        }
    }

  private:
    fs::path destination_;
    fs::path folder_;
};

}  // namespace

bool can_save_mesh_as(const fs::path& path) { return find_exporter_id(path) != nullptr; }

void save_mesh(const TriangleMesh& mesh, const fs::path& path) {
    const char* format = exporter_id(path);
    validate(mesh, path);
    // Only glTF keeps the materials' order, so only glTF keeps the surface ids.
    const bool gltf = std::string_view(format).starts_with("gl");
    const std::unique_ptr<aiScene> scene = make_scene(mesh, path.stem().string(), gltf);

    StagingFolder staging(path);
    Assimp::Exporter exporter;
    aiReturn result = aiReturn_FAILURE;
    try {
        result = exporter.Export(scene.get(), format, staging.staged_file().string());
    } catch (const std::exception& e) {
        fail_to_save(path, std::string("export failed: ") + e.what());
    }
    if (result != aiReturn_SUCCESS) fail_to_save(path, exporter.GetErrorString());
    staging.commit();
}

}  // namespace trackphys
