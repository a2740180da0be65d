#include "trackphys/io/regular_file.hpp"

#include <system_error>

#include "trackphys/error.hpp"

namespace trackphys {

void require_regular_file(const std::filesystem::path& path, const std::string& name) {
    namespace fs = std::filesystem;
    std::error_code error;
    const fs::file_status status = fs::status(path, error);
    if (!fs::exists(status)) throw Error(name + ": no such file");
    if (fs::is_directory(status)) throw Error(name + ": is a folder, not a file");
    if (!fs::is_regular_file(status)) throw Error(name + ": not a regular file");
}

}  // namespace trackphys
