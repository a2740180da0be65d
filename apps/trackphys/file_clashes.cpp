#include "file_clashes.hpp"

#include <system_error>

#include "trackphys/error.hpp"

namespace trackphys::cli {

namespace fs = std::filesystem;

namespace {

// Absolute first: weakly_canonical leaves a path relative when none of its leading parts
// exists ("x.json", not yet written) but makes "./x.json" absolute, so the two would differ.
fs::path resolved(const fs::path& path, std::error_code& error) {
    const fs::path absolute = fs::absolute(path, error);
    return error ? fs::path() : fs::weakly_canonical(absolute, error);
}

}  // namespace

bool same_file(const fs::path& a, const fs::path& b) {
    std::error_code error_a, error_b, error;
    const fs::path canonical_a = resolved(a, error_a);
    const fs::path canonical_b = resolved(b, error_b);
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
