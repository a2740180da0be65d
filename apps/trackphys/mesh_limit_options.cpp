#include "mesh_limit_options.hpp"

#include <cstddef>
#include <string>

namespace trackphys::cli {

namespace {

// A limit of 0 would refuse every mesh; a leading minus sign CLI11 would wrap into an
// unsigned option as 2^64 - 1.
CLI::Validator at_least_one() {
    return CLI::Validator(
        [](const std::string& text) {
            const bool positive =
                !text.empty() && text[0] != '-' && text.find_first_not_of('0') != std::string::npos;
            return positive ? std::string() : "must be >= 1, got " + text;
        },
        "", "at_least_one");
}

}  // namespace

void add_mesh_limit_options(CLI::App& command, MeshLoadLimits& limits) {
    const std::string group = "Mesh limits (a mesh file beyond one is refused)";
    command.add_option("--max-triangles", limits.max_triangles, "triangles in the loaded mesh")
        ->group(group)
        ->check(at_least_one())
        ->capture_default_str();
    command.add_option("--max-vertices", limits.max_vertices, "vertices in the loaded mesh")
        ->group(group)
        ->check(at_least_one())
        ->capture_default_str();
    command
        .add_option("--max-bytes", limits.max_bytes,
                    "bytes of the mesh file and the glTF buffer files it names")
        ->group(group)
        ->check(at_least_one())
        ->capture_default_str();
    command
        .add_option("--max-nesting", limits.max_nesting, "nesting of AC3D objects and glTF nodes")
        ->group(group)
        ->check(CLI::Range(std::size_t{1}, max_mesh_nesting_allowed))
        ->capture_default_str();
}

}  // namespace trackphys::cli
