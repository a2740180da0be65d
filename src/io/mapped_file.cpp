#include "io/mapped_file.hpp"

#include <cerrno>
#include <cstring>
#include <string>

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include "trackphys/error.hpp"

namespace trackphys::detail {

MappedFile::MappedFile(const std::filesystem::path& path, const char* kind) {
    const auto fail = [&path, kind](const char* what) {
        throw Error(std::string(kind) + " '" + path.string() + "': cannot " + what +
                    " it: " + std::strerror(errno));
    };
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) fail("open");
    struct stat status {};
    if (::fstat(fd, &status) != 0) {
        ::close(fd);
        fail("read the size of");
    }
    size_ = static_cast<std::size_t>(status.st_size);
    if (size_ > 0) {
        // Populated: every caller reads the whole file, and one call that maps all its pages
        // costs less than a fault for each.
        data_ = ::mmap(nullptr, size_, PROT_READ, MAP_PRIVATE | MAP_POPULATE, fd, 0);
        if (data_ == MAP_FAILED) {
            data_ = nullptr;
            ::close(fd);
            fail("map");
        }
    }
    ::close(fd);
}

MappedFile::~MappedFile() {
    if (data_ != nullptr) ::munmap(data_, size_);
}

}  // namespace trackphys::detail
