#include "io/file_bytes.hpp"

#include <cerrno>
#include <cstring>
#include <memory>
#include <new>
#include <string>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include "trackphys/error.hpp"

namespace trackphys::detail {

FileBytes::FileBytes(const std::filesystem::path& path, const char* kind,
                     const std::function<void(std::uintmax_t)>& check_size) {
    const std::string name = std::string(kind) + " '" + path.string() + "'";
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) throw Error(name + ": cannot open it: " + std::strerror(errno));
    // Closes the file on every way out, the throws included.
    const std::unique_ptr<const int, void (*)(const int*)> closer(
        &fd, [](const int* f) { ::close(*f); });
    struct stat status {};
    if (::fstat(fd, &status) != 0)
        throw Error(name + ": cannot read the size of it: " + std::strerror(errno));
    if (check_size) check_size(static_cast<std::uintmax_t>(status.st_size));
    size_ = static_cast<std::size_t>(status.st_size);
    try {
        data_ = std::make_unique_for_overwrite<char[]>(size_);
    } catch (const std::bad_alloc&) {
        throw Error(name + ": cannot hold its " + std::to_string(size_) + " bytes in memory");
    }
    for (std::size_t done = 0; done < size_;) {
        const ::ssize_t got = ::read(fd, data_.get() + done, size_ - done);
        if (got < 0 && errno == EINTR) continue;
        if (got < 0) throw Error(name + ": cannot read it: " + std::strerror(errno));
        if (got == 0)
            throw Error(name + ": it shrank from " + std::to_string(size_) + " to " +
                        std::to_string(done) +
                        " bytes while it was read (another program is writing it)");
        done += static_cast<std::size_t>(got);
    }
}

}  // namespace trackphys::detail
