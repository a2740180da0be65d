#pragma once

// Small static worlds for the physics tests: flat ground, a wall, a single-triangle road;
// a car's moving state, and a scene of two cars that touch.

#include <cstdint>
#include <memory>

#include "trackphys/collision/static_world.hpp"
#include "trackphys/dynamics/car_spec.hpp"
#include "trackphys/dynamics/rigid_body.hpp"
#include "trackphys/geometry/triangle_mesh.hpp"
#include "trackphys/world/world.hpp"

namespace trackphys::test {

/// Flat ground at height y over [x0, x1] x [z0, z1], in nx x nz rectangles of two
/// triangles each, normals up: the finer, the more seams a car crosses.
inline TriangleMesh flat_grid(double x0, double x1, double z0, double z1, int nx, int nz,
                              double y = 0.0) {
    TriangleMesh mesh;
    for (int i = 0; i <= nx; ++i)
        for (int j = 0; j <= nz; ++j)
            mesh.vertices.push_back({x0 + (x1 - x0) * i / nx, y, z0 + (z1 - z0) * j / nz});
    const auto at = [&](int i, int j) { return static_cast<std::uint32_t>(i * (nz + 1) + j); };
    for (int i = 0; i < nx; ++i)
        for (int j = 0; j < nz; ++j) {
            // (x, z) counter-clockwise seen from above (+Y): +z first, then +x.
            mesh.triangles.push_back({at(i, j), at(i, j + 1), at(i + 1, j + 1)});
            mesh.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i + 1, j)});
        }
    return mesh;
}

/// A flat square of ground centred on (0, y, 0), size metres wide, in cells x cells squares.
inline TriangleMesh flat_grid(double size, int cells, double y = 0.0) {
    return flat_grid(-0.5 * size, 0.5 * size, -0.5 * size, 0.5 * size, cells, cells, y);
}

/// A long straight road along +Z from z = 0 to z = length, width wide, in cells of about
/// cell metres, at height 0.
inline TriangleMesh straight_road(double length, double width, double cell) {
    return flat_grid(-0.5 * width, 0.5 * width, 0.0, length, static_cast<int>(width / cell),
                     static_cast<int>(length / cell));
}

/// A vertical wall across +Z at z = z0, facing -Z (towards a car coming from z < z0),
/// width wide and height tall, as two triangles.
inline TriangleMesh wall(double z0, double width, double height) {
    TriangleMesh mesh;
    mesh.vertices = {{-0.5 * width, -1.0, z0},
                     {0.5 * width, -1.0, z0},
                     {0.5 * width, height, z0},
                     {-0.5 * width, height, z0}};
    mesh.triangles = {{0, 2, 1}, {0, 3, 2}};
    return mesh;
}

inline std::shared_ptr<const StaticWorld> static_world_of(const TriangleMesh& mesh) {
    auto world = std::make_shared<StaticWorld>();
    world->add(std::make_shared<StaticCollider>(mesh));
    return world;
}

/// A body at `position` (upright, not turning) moving at `velocity`.
inline RigidBodyState moving(const glm::dvec3& position, const glm::dvec3& velocity) {
    RigidBodyState state;
    state.position = position;
    state.linear_velocity = velocity;
    return state;
}

/// No static world and no gravity (besides `base`'s settings): cars meet only each other.
/// Car 0 is far away; cars 1 and 2, without air drag, meet head on at 10 m/s each.
inline World head_on_in_free_space(const WorldSettings& base = {}) {
    WorldSettings settings = base;
    settings.gravity = glm::dvec3(0.0);
    World world(std::make_shared<StaticWorld>(), settings);
    CarSpec spec = CarSpec::default_car();
    spec.air_density = 0.0;
    world.add_car(spec, moving({100.0, 0.0, 0.0}, {0.0, 0.0, 10.0}));
    world.add_car(spec, moving({0.0, 0.0, 0.0}, {0.0, 0.0, 10.0}));
    world.add_car(spec, moving({0.0, 0.0, 8.0}, {0.0, 0.0, -10.0}));
    return world;
}

/// Car 1 drives into the back of car 0, which brakes, on flat ground.
inline World one_car_pushing_a_braked_one() {
    World world(static_world_of(flat_grid(400.0, 40)));
    const CarSpec spec = CarSpec::default_car();
    const double y = spec.lowest_point_depth() + 0.001;
    world.add_car(spec, moving({0.0, y, 0.0}, glm::dvec3(0.0)));
    world.add_car(spec, moving({0.0, y, -8.0}, {0.0, 0.0, 4.0}));
    world.car(0).set_inputs({0.0, 1.0, 0.0});
    world.car(1).set_inputs({0.6, 0.0, 0.0});
    return world;
}

}  // namespace trackphys::test
