#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <exception>
#include <limits>
#include <memory>
#include <string>
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
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
        for (const std::uint32_t i : mesh.triangles[t])
            if (i >= mesh.vertices.size())
                fail(path, "triangle " + std::to_string(t) + " refers to missing vertex " +
                               std::to_string(i));
}

// One node holding one mesh with one default material: the smallest scene every assimp
// exporter accepts (the glTF and OBJ exporters index mMaterials unconditionally).
// aiScene's destructor frees everything reachable from it, hence the raw new[].
std::unique_ptr<aiScene> make_scene(const TriangleMesh& mesh, const std::string& name) {
    auto scene = std::make_unique<aiScene>();
    scene->mRootNode = new aiNode(name);
    scene->mRootNode->mNumMeshes = 1;
    scene->mRootNode->mMeshes = new unsigned[1]{0};

    scene->mNumMaterials = 1;
    scene->mMaterials = new aiMaterial* [1] { new aiMaterial() };

    auto* out = new aiMesh();
    scene->mNumMeshes = 1;
    scene->mMeshes = new aiMesh* [1] { out };
    out->mName = aiString(name);
    out->mMaterialIndex = 0;
    out->mPrimitiveTypes = aiPrimitiveType_TRIANGLE;
    out->mNumVertices = static_cast<unsigned>(mesh.vertices.size());
    out->mVertices = new aiVector3D[mesh.vertices.size()];
    for (std::size_t v = 0; v < mesh.vertices.size(); ++v) {
        const glm::dvec3& p = mesh.vertices[v];
        // Nearest float32: the only precision assimp's formats hold (see mesh_io.hpp).
        out->mVertices[v] =
            aiVector3D(static_cast<float>(p.x), static_cast<float>(p.y), static_cast<float>(p.z));
    }
    out->mNumFaces = static_cast<unsigned>(mesh.triangles.size());
    out->mFaces = new aiFace[mesh.triangles.size()];
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
        aiFace& face = out->mFaces[t];
        face.mNumIndices = 3;
        face.mIndices =
            new unsigned[3]{mesh.triangles[t][0], mesh.triangles[t][1], mesh.triangles[t][2]};
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
    const std::unique_ptr<aiScene> scene = make_scene(mesh, path.stem().string());

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
