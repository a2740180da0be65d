#pragma once

#include <cstdint>

#include <glm/vec3.hpp>

#include "trackphys/geometry/triangle_mesh.hpp"

namespace trackphys::test {

/// A grid of rows x columns quads, two triangles each, over the (rows + 1) x (columns + 1)
/// vertices vertex(r, c) (glm::dvec3), row by row: a height field for tests and benchmarks
/// that need many triangles of one shape. Each quad is split along its (r, c)-(r + 1, c + 1)
/// diagonal, both triangles wound from row r towards row r + 1.
template <class Vertex>
TriangleMesh grid_mesh(int rows, int columns, Vertex vertex) {
    TriangleMesh mesh;
    for (int r = 0; r <= rows; ++r)
        for (int c = 0; c <= columns; ++c) mesh.vertices.push_back(glm::dvec3(vertex(r, c)));
    const auto at = [&](int r, int c) { return static_cast<std::uint32_t>(r * (columns + 1) + c); };
    for (int r = 0; r < rows; ++r)
        for (int c = 0; c < columns; ++c) {
            mesh.triangles.push_back({at(r, c), at(r + 1, c), at(r + 1, c + 1)});
            mesh.triangles.push_back({at(r, c), at(r + 1, c + 1), at(r, c + 1)});
        }
    return mesh;
}

}  // namespace trackphys::test
