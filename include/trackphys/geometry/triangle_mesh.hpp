#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

namespace trackphys {

/// An indexed triangle mesh in world space (metres): the exchange format between the track
/// generator, mesh import/export and static colliders.
struct TriangleMesh {
    std::vector<glm::dvec3> vertices;
    std::vector<std::array<std::uint32_t, 3>> triangles;  ///< indices into vertices, CCW
};

}  // namespace trackphys
