#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include <glm/vec3.hpp>

#include "trackphys/math/types.hpp"

namespace trackphys {

/// What a triangle is made of (road, grass, gravel, kerb, ice...): an index into the game's
/// table of surfaces, WorldSettings::surfaces. The ids are geometry, fixed with the mesh;
/// the table is tuning (docs/design.md#surfaces).
using SurfaceId = std::uint16_t;
/// How many surface ids there are: the most entries a surface table holds.
inline constexpr std::size_t max_surfaces = std::size_t{std::numeric_limits<SurfaceId>::max()} + 1;

/// An indexed triangle mesh in world space (metres): the exchange format between the track
/// generator, mesh import/export and static colliders.
struct TriangleMesh {
    std::vector<glm::dvec3> vertices;
    std::vector<std::array<std::uint32_t, 3>> triangles;  ///< indices into vertices, CCW
    /// One surface id per triangle, in triangle order; empty: every triangle is surface 0.
    std::vector<SurfaceId> surfaces{};
};

}  // namespace trackphys
