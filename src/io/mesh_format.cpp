#include "io/mesh_format.hpp"

#include <array>
#include <cctype>

namespace trackphys::detail {
namespace {

struct FormatName {
    const char* extension;
    MeshFormat format;
};

// AC3D has three extensions in use (.ac most, .acc and .ac3d by some exporters).
constexpr std::array<FormatName, 9> kFormats{{
    {".obj", MeshFormat::obj},
    {".ply", MeshFormat::ply},
    {".stl", MeshFormat::stl},
    {".gltf", MeshFormat::gltf},
    {".glb", MeshFormat::glb},
    {".ac", MeshFormat::ac3d},
    {".acc", MeshFormat::ac3d},
    {".ac3d", MeshFormat::ac3d},
    {".off", MeshFormat::off},
}};

}  // namespace

std::optional<MeshFormat> mesh_format_of(const std::filesystem::path& path) {
    std::string extension = path.extension().string();
    for (char& ch : extension) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
    for (const FormatName& f : kFormats)
        if (extension == f.extension) return f.format;
    return std::nullopt;
}

std::string read_mesh_extensions() {
    std::string list;
    for (const FormatName& f : kFormats)
        list += (list.empty() ? "" : ", ") + std::string(f.extension);
    return list;
}

const char* assimp_reader_name(MeshFormat format) {
    switch (format) {
        case MeshFormat::obj:
            return "Wavefront Object Importer";
        case MeshFormat::ply:
            return "Stanford Polygon Library (PLY) Importer";
        case MeshFormat::stl:
            return "Stereolithography (STL) Importer";
        // Not "glTF Importer": that one reads glTF 1, and its CanRead parses the whole file.
        case MeshFormat::gltf:
        case MeshFormat::glb:
            return "glTF2 Importer";
        case MeshFormat::ac3d:
            return "AC3D Importer";
        case MeshFormat::off:
            return "OFF Importer";
    }
    return "";
}

}  // namespace trackphys::detail
