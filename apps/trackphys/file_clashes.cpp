#include "file_clashes.hpp"

#include <system_error>

#include "trackphys/error.hpp"

namespace trackphys::cli {

namespace fs = std::filesystem;

bool same_file(const fs::path& a, const fs::path& b) {
    std::error_code error_a, error_b, error;
    const fs::path canonical_a = fs::weakly_canonical(a, error_a);
    const fs::path canonical_b = fs::weakly_canonical(b, error_b);
    if (!error_a && !error_b && canonical_a == canonical_b) return true;
    // False, with an error, unless both exist.
    return fs::equivalent(a, b, error);
}

void refuse_file_clashes(std::initializer_list<NamedFile> inputs,
                         std::initializer_list<NamedFile> outputs) {
    for (auto output = outputs.begin(); output != outputs.end(); ++output) {
        if (output->path.empty()) continue;
        const std::string name = output->option + " '" + output->path.string() + "': ";
        for (const NamedFile& input : inputs)
            if (!input.path.empty() && same_file(output->path, input.path))
                throw Error(name + "the same file as " + input.option + " '" + input.path.string() +
                            "', which it would overwrite");
        for (auto other = outputs.begin(); other != output; ++other)
            if (!other->path.empty() && same_file(output->path, other->path))
                throw Error(name + "the same file as " + other->option + " '" +
                            other->path.string() + "', which it writes too");
    }
}

}  // namespace trackphys::cli
