// World::add_car gives the cars of one spec one shared copy of their body-frame ellipsoids
// (Car::share_ellipsoids_with), and a restored world shares the same way.
#include <memory>

#include <gtest/gtest.h>

#include "support/shared_ellipsoids.hpp"
#include "trackphys/world/world.hpp"

namespace trackphys {
namespace {

using test::share_one_copy;

RigidBodyState at(double x) {
    RigidBodyState state;
    state.position = glm::dvec3(x, 0.0, 0.0);
    return state;
}

// Cars of two specs added in turn: a, b, a, b.
void add_two_kinds(World& world) {
    CarSpec other = CarSpec::default_car();
    other.ellipsoids[0].semi_axes.x *= 1.01;
    for (int i = 0; i < 4; ++i)
        world.add_car(i % 2 == 0 ? CarSpec::default_car() : other, at(10.0 * i));
}

void expect_shared_by_spec(const World& world) {
    EXPECT_TRUE(share_one_copy(world.car(0), world.car(2)));
    EXPECT_TRUE(share_one_copy(world.car(1), world.car(3)));
    EXPECT_FALSE(share_one_copy(world.car(0), world.car(1)));
}

TEST(WorldCarSharing, CarsOfOneSpecShareOneCopy) {
    World world(std::make_shared<StaticWorld>());
    add_two_kinds(world);
    expect_shared_by_spec(world);
}

TEST(WorldCarSharing, ARestoredWorldSharesTheSameWay) {
    World original(std::make_shared<StaticWorld>());
    add_two_kinds(original);
    original.update();
    World restored(std::make_shared<StaticWorld>());
    add_two_kinds(restored);
    restored.restore_state(original.save_state());
    expect_shared_by_spec(restored);
    // Nothing leaks between worlds: each world's cars build their own copy.
    EXPECT_FALSE(share_one_copy(original.car(0), restored.car(0)));
}

}  // namespace
}  // namespace trackphys
