#include "mesh_reading.hpp"

#include "counted_progress.hpp"

namespace trackphys::cli {

TriangleMesh read_mesh(const std::filesystem::path& file, MeshLoadReport& report,
                       const MeshLoadLimits& limits) {
    CountedProgress progress("triangles placed");
    return load_mesh(file, report, limits, progress.callback());
}

TriangleMesh read_mesh(const std::filesystem::path& file, const MeshLoadLimits& limits) {
    MeshLoadReport report;
    return read_mesh(file, report, limits);
}

}  // namespace trackphys::cli
