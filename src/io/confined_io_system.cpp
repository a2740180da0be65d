#include "io/confined_io_system.hpp"

#include <algorithm>
#include <cstring>

#include <assimp/IOStream.hpp>

namespace trackphys::detail {
namespace {

namespace fs = std::filesystem;

// A read-only stream over bytes already in memory, behaving as a file stream would at its
// edges (assimp's own MemoryIOStream asserts on a zero-sized read, which Debian's build keeps
// on and which would abort the process).
class BytesStream : public Assimp::IOStream {
  public:
    explicit BytesStream(std::string_view bytes) : bytes_(bytes) {}

    size_t Read(void* out, size_t size, size_t count) override {
        if (size == 0) return 0;
        const size_t whole = std::min(count, (bytes_.size() - at_) / size);
        if (whole > 0) std::memcpy(out, bytes_.data() + at_, whole * size);
        at_ += whole * size;
        return whole;
    }
    size_t Write(const void*, size_t, size_t) override { return 0; }
    // Within the bytes only; aiOrigin_END counts back from the end, as assimp's streams do.
    aiReturn Seek(size_t offset, aiOrigin origin) override {
        const size_t size = bytes_.size();
        switch (origin) {
            case aiOrigin_SET:
                if (offset > size) return aiReturn_FAILURE;
                at_ = offset;
                return aiReturn_SUCCESS;
            case aiOrigin_CUR:
                if (offset > size - at_) return aiReturn_FAILURE;
                at_ += offset;
                return aiReturn_SUCCESS;
            case aiOrigin_END:
                if (offset > size) return aiReturn_FAILURE;
                at_ = size - offset;
                return aiReturn_SUCCESS;
            default:
                return aiReturn_FAILURE;
        }
    }
    size_t Tell() const override { return at_; }
    size_t FileSize() const override { return bytes_.size(); }
    void Flush() override {}

  private:
    std::string_view bytes_;
    size_t at_ = 0;
};

}  // namespace

ConfinedIoSystem::ConfinedIoSystem(const fs::path& mesh_file, std::string_view mesh_bytes,
                                   const std::set<fs::path>& buffers)
    : mesh_file_(mesh_file.lexically_normal()), mesh_bytes_(mesh_bytes) {
    for (const fs::path& buffer : buffers) buffers_.insert(buffer.lexically_normal());
}

bool ConfinedIoSystem::is_mesh(const char* file) const {
    return file != nullptr && fs::path(file).lexically_normal() == mesh_file_;
}

bool ConfinedIoSystem::allowed(const char* file) const {
    return file != nullptr && buffers_.count(fs::path(file).lexically_normal()) > 0;
}

bool ConfinedIoSystem::Exists(const char* file) const {
    return is_mesh(file) || (allowed(file) && DefaultIOSystem::Exists(file));
}

Assimp::IOStream* ConfinedIoSystem::Open(const char* file, const char* mode) {
    // Reading only: assimp's readers never write, and nothing here should.
    if (std::string_view(mode).find_first_of("wa+") != std::string_view::npos) return nullptr;
    if (is_mesh(file)) return new BytesStream(mesh_bytes_);  // assimp deletes it (Close)
    if (!allowed(file)) return nullptr;
    return DefaultIOSystem::Open(file, mode);
}

}  // namespace trackphys::detail
