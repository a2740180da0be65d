#pragma once

// Small static worlds for the physics tests: flat ground, a wall, a single-triangle road.

#include <cstdint>
#include <memory>

#include "trackphys/collision/static_world.hpp"
#include "trackphys/geometry/triangle_mesh.hpp"

namespace trackphys::test {

/// A flat square of ground at height y, centred on (0, y, 0), of cells x cells squares
/// (two triangles each, normals up): the finer, the more seams a car crosses.
inline TriangleMesh flat_grid(double size, int cells, double y = 0.0) {
    TriangleMesh mesh;
    const double step = size / cells;
    for (int i = 0; i <= cells; ++i)
        for (int j = 0; j <= cells; ++j)
            mesh.vertices.push_back({-0.5 * size + i * step, y, -0.5 * size + j * step});
    const auto at = [&](int i, int j) { return static_cast<std::uint32_t>(i * (cells + 1) + j); };
    for (int i = 0; i < cells; ++i)
        for (int j = 0; j < cells; ++j) {
            // (x, z) counter-clockwise seen from above (+Y): x then -z.
            mesh.triangles.push_back({at(i, j), at(i, j + 1), at(i + 1, j + 1)});
            mesh.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i + 1, j)});
        }
    return mesh;
}

/// A long straight road along +Z from z = 0 to z = length, width wide, in cells of about
/// cell metres, at height 0.
inline TriangleMesh straight_road(double length, double width, double cell) {
    TriangleMesh mesh;
    const int along = static_cast<int>(length / cell);
    const int across = static_cast<int>(width / cell);
    for (int i = 0; i <= across; ++i)
        for (int j = 0; j <= along; ++j)
            mesh.vertices.push_back({-0.5 * width + width * i / across, 0.0, length * j / along});
    const auto at = [&](int i, int j) { return static_cast<std::uint32_t>(i * (along + 1) + j); };
    for (int i = 0; i < across; ++i)
        for (int j = 0; j < along; ++j) {
            mesh.triangles.push_back({at(i, j), at(i, j + 1), at(i + 1, j + 1)});
            mesh.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i + 1, j)});
        }
    return mesh;
}

/// A vertical wall across +Z at z = z0, facing -Z (towards a car coming from z < z0),
/// width wide and height tall, as two triangles.
inline TriangleMesh wall(double z0, double width, double height) {
    TriangleMesh mesh;
    mesh.vertices = {{-0.5 * width, -1.0, z0}, {0.5 * width, -1.0, z0},
                     {0.5 * width, height, z0}, {-0.5 * width, height, z0}};
    mesh.triangles = {{0, 2, 1}, {0, 3, 2}};
    return mesh;
}

inline std::shared_ptr<const StaticWorld> static_world_of(const TriangleMesh& mesh) {
    auto world = std::make_shared<StaticWorld>();
    world->add(std::make_shared<StaticCollider>(mesh));
    return world;
}

}  // namespace trackphys::test
