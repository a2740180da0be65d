#include "staged_outputs.hpp"

#include <cerrno>
#include <cstdlib>
#include <system_error>

#include <sys/stat.h>
#include <unistd.h>

#include "trackphys/error.hpp"

namespace trackphys::cli {

namespace fs = std::filesystem;

StagedOutputs::~StagedOutputs() {
    std::error_code ignored;
    for (const Staged& s : staged_) fs::remove(s.temporary, ignored);
}

void check_destination(const fs::path& destination, const std::string& option) {
    const std::string name = option + " '" + destination.string() + "'";
    if (destination.filename().empty() || destination.filename() == "." ||
        destination.filename() == "..")
        throw Error(name + ": not a file name");
    std::error_code error;
    const fs::path folder = destination.has_parent_path() ? destination.parent_path() : ".";
    if (!fs::is_directory(folder, error))
        throw Error(name + ": folder '" + folder.string() + "' does not exist");
    const fs::file_status existing = fs::symlink_status(destination, error);
    if (fs::is_directory(existing)) throw Error(name + ": is a folder");
    // The rename would replace it: never a device (/dev/null as root), a pipe or a link.
    if (fs::exists(existing) && !fs::is_regular_file(existing))
        throw Error(name + ": exists and is not a regular file");
}

fs::path StagedOutputs::stage(const fs::path& destination, const std::string& option) {
    check_destination(destination, option);
    const std::string name = option + " '" + destination.string() + "'";
    const fs::path folder = destination.has_parent_path() ? destination.parent_path() : ".";
    // A hidden name in the same folder: the same file system, so the final rename is atomic.
    // Appended piecewise: GCC 12 warns falsely (-Wrestrict) on "." + std::string.
    std::string hidden = ".";
    hidden += destination.filename().string();
    hidden += ".tmp-XXXXXX";
    std::string pattern = (folder / hidden).string();
    const int fd = ::mkstemp(pattern.data());
    if (fd < 0)
        throw Error(name + ": cannot create a file in '" + folder.string() +
                    "': " + std::generic_category().message(errno));
    // mkstemp makes the file private (0600); an output gets the mode any new file would.
    const mode_t mask = ::umask(0);
    ::umask(mask);
    ::fchmod(fd, 0666 & ~mask);
    ::close(fd);
    staged_.push_back({destination, pattern, option});
    return pattern;
}

void StagedOutputs::commit() {
    for (std::size_t i = 0; i < staged_.size(); ++i) {
        std::error_code error;
        fs::rename(staged_[i].temporary, staged_[i].destination, error);
        if (!error) continue;
        std::error_code ignored;
        for (std::size_t j = 0; j < i; ++j) fs::remove(staged_[j].destination, ignored);
        throw Error(staged_[i].option + " '" + staged_[i].destination.string() +
                    "': cannot move the written file into place: " + error.message());
    }
    staged_.clear();
}

}  // namespace trackphys::cli
