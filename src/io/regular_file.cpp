#include "trackphys/io/regular_file.hpp"

#include <algorithm>
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

bool lies_inside(const std::filesystem::path& file, const std::filesystem::path& folder) {
    namespace fs = std::filesystem;
    std::error_code error;
    const fs::path real_file = fs::canonical(file, error);
    if (error) return false;
    const fs::path real_folder = fs::canonical(folder, error);
    if (error) return false;
    const auto [in_folder, in_file] =
        std::mismatch(real_folder.begin(), real_folder.end(), real_file.begin(), real_file.end());
    return in_folder == real_folder.end() && in_file != real_file.end();
}

}  // namespace trackphys
