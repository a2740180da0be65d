// Surfaces and contact events: a road whose right lane is ice past z = 10 m (surface 1, grip
// 0.15 in the world's table), a wall across both lanes at z = 60 m. Two cars brake fully from
// 20 m/s at z = 10 m: the dry one stops, the one on ice slides into the wall, and the world
// reports that hit as an event, with the triangle and the speed a damage model wants.
#include <cstdint>
#include <cstdio>
#include <memory>
#include <optional>

#include <trackphys/world/spawn.hpp>
#include <trackphys/world/world.hpp>

using namespace trackphys;

constexpr SurfaceId kAsphalt = 0, kIce = 1;

// A flat quad at y = 0, facing up, as two triangles of one surface.
void add_quad(TriangleMesh& mesh, double x0, double x1, double z0, double z1, SurfaceId surface) {
    const auto first = static_cast<std::uint32_t>(mesh.vertices.size());
    mesh.vertices.insert(mesh.vertices.end(), {{x0, 0, z0}, {x1, 0, z0}, {x1, 0, z1}, {x0, 0, z1}});
    mesh.triangles.push_back({first, first + 3, first + 2});
    mesh.triangles.push_back({first, first + 2, first + 1});
    mesh.surfaces.insert(mesh.surfaces.end(), {surface, surface});
}

int main() {
    TriangleMesh road;                          // the cars face +Z; +X is their left
    add_quad(road, 0, 10, -20, 100, kAsphalt);  // left lane
    add_quad(road, -10, 0, -20, 10, kAsphalt);  // right lane, then ice
    add_quad(road, -10, 0, 10, 100, kIce);
    TriangleMesh wall;  // across both lanes at z = 60 m, facing the cars (-Z)
    wall.vertices = {{-10, -1, 60}, {10, -1, 60}, {10, 3, 60}, {-10, 3, 60}};
    wall.triangles = {{0, 2, 1}, {0, 3, 2}};

    auto statics = std::make_shared<StaticWorld>();
    statics->add(std::make_shared<StaticCollider>(road));  // collider 0
    statics->add(std::make_shared<StaticCollider>(wall));  // collider 1 (surface 0)
    WorldSettings settings;
    settings.surfaces = {Surface{.grip = 1.0}, Surface{.grip = 0.15}};  // by SurfaceId
    World world(statics, settings);

    const CarSpec spec = CarSpec::default_car();
    for (const double x : {5.0, -5.0}) {  // car 0 on asphalt, car 1 on the iced lane
        RigidBodyState start =
            place_car_on_surface(*statics, spec, {x, 2.0, 10.0}, glm::dquat(1.0, 0.0, 0.0, 0.0));
        start.linear_velocity = {0.0, 0.0, 20.0};
        world.add_car(spec, start);
        world.car(world.car_count() - 1).set_inputs({.throttle = 0.0, .brake = 1.0, .steer = 0.0});
    }
    int hits = 0;
    for (int update = 1; update <= 600 && hits == 0; ++update) {
        world.update();
        for (const BodyHitEvent& hit : world.contact_events().body_hits) {
            std::printf("update %d: car %u hit collider %u's triangle %u at %.1f m/s\n", update,
                        hit.car, hit.triangle.collider, hit.triangle.triangle, hit.approach_speed);
            hits += hit.car == 1 && hit.triangle.collider == 1;
        }
    }
    const std::optional<ContactSurface> wheel = world.contact_surface(1, 0);
    const double dry_stop = world.car(0).state().position.z - 10.0;
    std::printf(
        "dry car stopped after %.1f m; the car on ice (its wheel 0 on surface %u) hit "
        "the wall %s\n",
        dry_stop, wheel ? unsigned{wheel->surface} : 99u, hits ? "once" : "never");
    return hits == 1 && dry_stop < 30.0 && wheel && wheel->surface == kIce ? 0 : 1;
}
