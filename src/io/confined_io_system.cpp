#include "io/confined_io_system.hpp"

#include <string_view>

namespace trackphys::detail {

namespace fs = std::filesystem;

ConfinedIoSystem::ConfinedIoSystem(const fs::path& mesh_file, const std::set<fs::path>& buffers) {
    allowed_.insert(mesh_file.lexically_normal());
    for (const fs::path& buffer : buffers) allowed_.insert(buffer.lexically_normal());
}

bool ConfinedIoSystem::allowed(const char* file) const {
    return file != nullptr && allowed_.count(fs::path(file).lexically_normal()) > 0;
}

bool ConfinedIoSystem::Exists(const char* file) const {
    return allowed(file) && DefaultIOSystem::Exists(file);
}

Assimp::IOStream* ConfinedIoSystem::Open(const char* file, const char* mode) {
    // Reading only: assimp's readers never write, and nothing here should.
    if (!allowed(file) || std::string_view(mode).find_first_of("wa+") != std::string_view::npos)
        return nullptr;
    return DefaultIOSystem::Open(file, mode);
}

}  // namespace trackphys::detail
