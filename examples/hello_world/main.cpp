// The smallest trackphys program: a flat square of road, one car, one simulated second.
#include <cstdio>
#include <memory>

#include <glm/geometric.hpp>
#include <trackphys/world/world.hpp>

int main() {
    trackphys::TriangleMesh ground;  // 200 m x 200 m at y = 0, normals up (+Y)
    ground.vertices = {{-100, 0, -100}, {100, 0, -100}, {100, 0, 100}, {-100, 0, 100}};
    ground.triangles = {{0, 3, 2}, {0, 2, 1}};

    auto statics = std::make_shared<trackphys::StaticWorld>();
    statics->add(std::make_shared<trackphys::StaticCollider>(ground));
    trackphys::World world(statics);  // 10 ms updates of 10 steps x 4 sub-steps

    trackphys::RigidBodyState start;  // centre of mass (m), orientation, velocities
    start.position = {0.0, 0.6, 0.0};
    const std::size_t car = world.add_car(trackphys::CarSpec::default_car(), start);
    world.car(car).set_inputs({.throttle = 0.5, .brake = 0.0, .steer = 0.0});

    for (int i = 0; i < 100; ++i) world.update();  // one second

    const trackphys::RigidBodyState& s = world.car(car).state();
    std::printf("t = %.2f s  position = (%.3f, %.3f, %.3f) m  speed = %.2f m/s\n", world.time(),
                s.position.x, s.position.y, s.position.z, glm::length(s.linear_velocity));
}
