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

[[noreturn]] void fail(const fs::path& path, const std::string& reason) {
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
    fail(path, "unknown extension '" + path.extension().string() + "' (expected " +
                   std::string(saved_mesh_extensions) + ")");
}

// Rejects what no format can hold, before any file is created.
void validate(const TriangleMesh& mesh, const fs::path& path) {
    if (mesh.triangles.empty()) fail(path, "the mesh has no triangles");
    if (mesh.vertices.size() > std::numeric_limits<unsigned>::max())
        fail(path, "more vertices than assimp's 32-bit indices address");
    constexpr double float_max = std::numeric_limits<float>::max();
    for (std::size_t v = 0; v < mesh.vertices.size(); ++v) {
        const glm::dvec3& p = mesh.vertices[v];
        if (!is_finite(p)) fail(path, "vertex " + std::to_string(v) + " is not finite");
        if (std::abs(p.x) > float_max || std::abs(p.y) > float_max || std::abs(p.z) > float_max)
            fail(path, "vertex " + std::to_string(v) + " lies beyond float32 range");
    }
    if (!mesh.surfaces.empty() && mesh.surfaces.size() != mesh.triangles.size())
        fail(path, std::to_string(mesh.surfaces.size()) + " surface ids for " +
                       std::to_string(mesh.triangles.size()) + " triangles");
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
        for (const std::uint32_t i : mesh.triangles[t])
            if (i >= mesh.vertices.size())
                fail(path, "triangle " + std::to_string(t) + " refers to missing vertex " +
                               std::to_string(i));
}

// An aiMesh of the mesh's triangles that `keep` takes, with the vertices they use
// (renumbered in order of first use; all of them, unrenumbered, when every triangle is kept).
template <class Keep>
aiMesh* make_mesh(const TriangleMesh& mesh, const std::string& name, unsigned material, Keep keep) {
    auto* out = new aiMesh();
    out->mName = aiString(name);
    out->mMaterialIndex = material;
    out->mPrimitiveTypes = aiPrimitiveType_TRIANGLE;
    std::vector<std::uint32_t> used;  // new vertex -> mesh vertex
    std::vector<std::uint32_t> renumbered(mesh.vertices.size(), ~0u);
    std::vector<std::size_t> triangles;
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
        if (!keep(t)) continue;
        triangles.push_back(t);
        for (const std::uint32_t v : mesh.triangles[t])
            if (renumbered[v] == ~0u) {
                renumbered[v] = static_cast<std::uint32_t>(used.size());
                used.push_back(v);
            }
    }
    if (triangles.size() == mesh.triangles.size()) {  // one mesh: the vertices as they are
        used.resize(mesh.vertices.size());
        for (std::uint32_t v = 0; v < used.size(); ++v) renumbered[v] = used[v] = v;
    }
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
    return out;
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
// destructor frees everything reachable from it, hence the raw new[].
std::unique_ptr<aiScene> make_scene(const TriangleMesh& mesh, const std::string& name,
                                    bool by_surface) {
    const SurfaceId highest = by_surface ? highest_of_contiguous_surfaces(mesh) : SurfaceId{0};
    const unsigned materials = unsigned(highest) + 1;
    std::vector<aiMesh*> meshes;
    if (highest == 0)
        meshes.push_back(make_mesh(mesh, name, 0, [](std::size_t) { return true; }));
    else
        for (unsigned id = 0; id < materials; ++id)
            meshes.push_back(make_mesh(mesh, name + " surface " + std::to_string(id), id,
                                       [&](std::size_t t) { return mesh.surfaces[t] == id; }));

    auto scene = std::make_unique<aiScene>();
    scene->mRootNode = new aiNode(name);
    scene->mRootNode->mNumMeshes = static_cast<unsigned>(meshes.size());
    scene->mRootNode->mMeshes = new unsigned[meshes.size()];
    for (unsigned m = 0; m < meshes.size(); ++m) scene->mRootNode->mMeshes[m] = m;
    scene->mNumMeshes = static_cast<unsigned>(meshes.size());
    scene->mMeshes = new aiMesh*[meshes.size()];
    std::copy(meshes.begin(), meshes.end(), scene->mMeshes);

    scene->mNumMaterials = materials;
    scene->mMaterials = new aiMaterial*[materials];
    for (unsigned id = 0; id < materials; ++id) {
        scene->mMaterials[id] = new aiMaterial();
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
            fail(destination, "cannot create a temporary folder in '" + parent.string() +
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
            fail(destination_, "cannot move the written file into place: " + e.code().message());
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
        fail(path, std::string("export failed: ") + e.what());
    }
    if (result != aiReturn_SUCCESS) fail(path, exporter.GetErrorString());
    staging.commit();
}

}  // namespace trackphys
