#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <string_view>

namespace trackphys::detail {

/// A whole file's bytes, read once into memory: the checks of mesh_checks.hpp walk them and
/// assimp reads the same bytes (so a file swapped in under its name after the check is never
/// read), and a map file decodes from them. Read, not mapped: a mapping's pages vanish when
/// another program truncates the file during the load (an updater rewriting a map in
/// place), and the next read of one kills the process with SIGBUS; a read that comes up
/// short is an error instead.
class FileBytes {
  public:
    /// Throws trackphys::Error naming the file ("<kind> '<path>': cannot open it: ...") when
    /// it cannot be opened or read, or shrinks while it is read. `check_size`, given, is
    /// called with the size of the file opened before a byte is read or allocated (a byte
    /// limit): what it throws propagates.
    explicit FileBytes(const std::filesystem::path& path, const char* kind = "mesh file",
                       const std::function<void(std::uintmax_t)>& check_size = {});

    std::string_view bytes() const { return {data_.get(), size_}; }

  private:
    std::unique_ptr<char[]> data_;
    std::size_t size_ = 0;
};

}  // namespace trackphys::detail
