// check_mesh (mesh_checks.hpp): the strict check of a file's format.

#include "io/mesh_checks.hpp"

namespace trackphys::detail {

std::set<std::filesystem::path> check_mesh(std::string_view file, MeshFormat format,
                                           const std::filesystem::path& folder,
                                           std::size_t max_nesting) {
    switch (format) {
        case MeshFormat::ply:
            check_ply(file);
            break;
        case MeshFormat::stl:
            check_stl(file);
            break;
        case MeshFormat::obj:
            check_obj(file);
            break;
        case MeshFormat::off:
            check_off(file);
            break;
        case MeshFormat::ac3d:
            check_ac3d(file, max_nesting);
            break;
        case MeshFormat::gltf:
            return check_gltf(file, false, folder, max_nesting);
        case MeshFormat::glb:
            return check_gltf(file, true, folder, max_nesting);
    }
    return {};
}

}  // namespace trackphys::detail
