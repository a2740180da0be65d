#pragma once

#include <string>

#include "trackphys/error.hpp"
#include "trackphys/geometry/triangle_mesh.hpp"

namespace trackphys::detail {

/// Throws unless `mesh` has one surface id per triangle or none (all surface 0).
inline void check_surface_count(const TriangleMesh& mesh) {
    if (!mesh.surfaces.empty() && mesh.surfaces.size() != mesh.triangles.size())
        throw Error("mesh has " + std::to_string(mesh.surfaces.size()) + " surface ids for " +
                    std::to_string(mesh.triangles.size()) +
                    " triangles (give one per triangle, or none for surface 0)");
}

}  // namespace trackphys::detail
