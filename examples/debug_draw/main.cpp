// What a game's renderer gets from World::debug_draw: after each update the world calls a
// DebugDraw of the game's with every car, its ellipsoids and their contacts (and, on request,
// the collision pipeline's boxes and triangles), which the game turns into its own lines and
// meshes. This one counts them and finds the deepest contact over a one-second drive.
#include <cstddef>
#include <cstdio>
#include <memory>

#include <trackphys/world/world.hpp>

using namespace trackphys;

class CountingDraw : public DebugDraw {
  public:
    void draw_ellipsoid(const DebugEllipsoid& e) override {
        ++ellipsoids;
        wheels += e.role != EllipsoidRole::body;
    }
    void draw_contact(const DebugContact& c) override {
        ++contacts;
        if (c.contact.depth > deepest) deepest = c.contact.depth;
    }
    void draw_kept_triangle(const DebugTriangle&, double) override { ++kept_triangles; }

    std::size_t ellipsoids = 0, wheels = 0, contacts = 0, kept_triangles = 0;
    double deepest = 0.0;
};

int main() {
    TriangleMesh ground;  // 200 m x 200 m at y = 0
    ground.vertices = {{-100, 0, -100}, {100, 0, -100}, {100, 0, 100}, {-100, 0, 100}};
    ground.triangles = {{0, 3, 2}, {0, 2, 1}};
    auto statics = std::make_shared<StaticWorld>();
    statics->add(std::make_shared<StaticCollider>(ground));
    World world(statics);
    RigidBodyState start;
    start.position = {0.0, 0.6, 0.0};
    world.add_car(CarSpec::default_car(), start);
    world.car(0).set_inputs({.throttle = 0.5, .brake = 0.0, .steer = 0.2});

    DebugDrawOptions options;  // cars, ellipsoids, contacts, car contacts; the triangles too:
    options.kept_triangles = true;
    CountingDraw draw;
    const int updates = 100;
    for (int i = 0; i < updates; ++i) {
        world.update();
        world.debug_draw(draw, options);  // between updates, on the thread that updates
    }
    std::printf(
        "per frame: %.1f ellipsoids (%.1f wheels), %.1f contacts, %.1f kept triangles; "
        "deepest contact %.1f mm\n",
        double(draw.ellipsoids) / updates, double(draw.wheels) / updates,
        double(draw.contacts) / updates, double(draw.kept_triangles) / updates,
        1000.0 * draw.deepest);
    // It starts a little above the ground and settles: most frames have all four wheels down.
    const bool wheels_on_the_ground = draw.contacts >= 3 * updates;
    return draw.wheels == 4 * updates && wheels_on_the_ground ? 0 : 1;
}
