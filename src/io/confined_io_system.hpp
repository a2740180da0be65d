#pragma once

#include <filesystem>
#include <set>
#include <string>
#include <string_view>

#include <assimp/DefaultIOSystem.h>

namespace trackphys::detail {

/// The files assimp may open while it reads one mesh: the mesh file itself, served from the
/// bytes its strict check walked (so the file is read once, and a file swapped in under the
/// same name between the check and the import is never seen), and the external buffers the
/// check accepted (a glTF's buffer URIs, each inside the mesh's folder; mesh_checks.hpp);
/// nothing else. Everything else is as if it did not exist: an OBJ's `mtllib` and any texture
/// or material stay unopened, since collision needs none of them, and no reference a check
/// missed can reach a file elsewhere.
class ConfinedIoSystem : public Assimp::DefaultIOSystem {
  public:
    /// mesh_bytes must outlive the importer that owns this IO system.
    ConfinedIoSystem(const std::filesystem::path& mesh_file, std::string_view mesh_bytes,
                     const std::set<std::filesystem::path>& buffers);

    bool Exists(const char* file) const override;
    Assimp::IOStream* Open(const char* file, const char* mode = "rb") override;

  private:
    bool is_mesh(const char* file) const;
    bool allowed(const char* file) const;

    std::filesystem::path mesh_file_;
    std::string_view mesh_bytes_;
    std::set<std::filesystem::path> buffers_;
};

}  // namespace trackphys::detail
