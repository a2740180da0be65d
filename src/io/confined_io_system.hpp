#pragma once

#include <filesystem>
#include <set>
#include <string>

#include <assimp/DefaultIOSystem.h>

namespace trackphys::detail {

/// The files assimp may open while it reads one mesh: the mesh file itself and the external
/// buffers its strict check accepted (a glTF's buffer URIs, each inside the mesh's folder;
/// gltf_check.hpp); nothing else. Everything else is as if it did not exist: an OBJ's
/// `mtllib` and any texture or material stay unopened, since collision needs none of them,
/// and no reference a check missed can reach a file elsewhere.
class ConfinedIoSystem : public Assimp::DefaultIOSystem {
  public:
    ConfinedIoSystem(const std::filesystem::path& mesh_file,
                     const std::set<std::filesystem::path>& buffers);

    bool Exists(const char* file) const override;
    Assimp::IOStream* Open(const char* file, const char* mode = "rb") override;

  private:
    bool allowed(const char* file) const;

    std::set<std::filesystem::path> allowed_;
};

}  // namespace trackphys::detail
