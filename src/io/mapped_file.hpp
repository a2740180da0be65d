#pragma once

#include <cstddef>
#include <filesystem>
#include <string_view>

namespace trackphys::detail {

/// A file's bytes mapped read-only: the checks of mesh_checks.hpp walk a whole file of any
/// size (a 50M-triangle track is gigabytes) without copying it into the heap, and a map
/// file loads without a heap copy of its bytes.
class MappedFile {
  public:
    /// Throws trackphys::Error naming the file ("<kind> '<path>': cannot open it: ...") when
    /// it cannot be opened or mapped.
    explicit MappedFile(const std::filesystem::path& path, const char* kind = "mesh file");
    ~MappedFile();
    MappedFile(const MappedFile&) = delete;
    MappedFile& operator=(const MappedFile&) = delete;

    std::string_view bytes() const { return {static_cast<const char*>(data_), size_}; }

  private:
    void* data_ = nullptr;
    std::size_t size_ = 0;
};

}  // namespace trackphys::detail
