// A car's next update box, computed at the end of its update (NextUpdateBoxes): it must be
// the box of the car's bits when the next update starts, whatever changed them in between.
#include "world/next_update_boxes.hpp"

#include <cstddef>
#include <cstring>
#include <memory>
#include <vector>

#include <gtest/gtest.h>

#include <glm/gtc/quaternion.hpp>

#include "trackphys/dynamics/car.hpp"
#include "trackphys/dynamics/car_spec.hpp"
#include "trackphys/world/debug_draw.hpp"
#include "trackphys/world/world.hpp"
#include "world/update_box.hpp"
#include "world/world_scenes.hpp"

namespace trackphys {
namespace {

bool same_bits(const Aabb& a, const Aabb& b) {
    return std::memcmp(&a.min, &b.min, sizeof a.min) == 0 &&
           std::memcmp(&a.max, &b.max, sizeof a.max) == 0;
}

RigidBodyState rolling(double x) {
    RigidBodyState state;
    state.position = {x, CarSpec::default_car().lowest_point_depth() + 0.001, 0.0};
    state.orientation = glm::normalize(glm::dquat(1.0, 0.0, 0.1, 0.0));
    state.linear_velocity = {0.0, 0.0, 12.0};
    state.angular_velocity = {0.0, 0.2, 0.0};
    return state;
}

TEST(NextUpdateBoxes, GivesTheBoxOfTheCarsBitsNow) {
    const WorldSettings settings;
    Car car(CarSpec::default_car(), rolling(0.0));
    detail::NextUpdateBoxes boxes;
    boxes.add_car(car.ellipsoid_count());
    EXPECT_TRUE(same_bits(boxes.box(0, car, settings), detail::car_update_box(car, settings)))
        << "a car with no box remembered";

    boxes.remember(0, car, settings);
    const Aabb remembered = detail::car_update_box(car, settings);
    EXPECT_TRUE(same_bits(boxes.box(0, car, settings), remembered));

    RigidBodyState moved = rolling(0.0);
    moved.position.x += 3.0;
    car.set_state(moved);
    const Aabb after_move = detail::car_update_box(car, settings);
    ASSERT_FALSE(same_bits(after_move, remembered));
    EXPECT_TRUE(same_bits(boxes.box(0, car, settings), after_move)) << "a state set since";

    boxes.remember(0, car, settings);
    std::vector<double> travel(car.suspension().begin(), car.suspension().end());
    for (std::size_t i = 0; i < travel.size(); ++i)
        if (car.spec().ellipsoids[i].role != EllipsoidRole::body)
            travel[i] = 0.5 * car.spec().suspension.travel;
    car.set_suspension(travel);
    const Aabb after_travel = detail::car_update_box(car, settings);
    ASSERT_FALSE(same_bits(after_travel, after_move));
    EXPECT_TRUE(same_bits(boxes.box(0, car, settings), after_travel)) << "a suspension set since";
}

class BoxLog : public DebugDraw {
  public:
    std::vector<Aabb> boxes;
    void draw_update_box(std::size_t, const Aabb& box) override { boxes.push_back(box); }
};

// Two cars rolling on flat ground; the game moves one between updates. Its update must
// query the box of where it was put (a stale box is widened during the update and shows
// as a different box), and the world must go on as one restored from a snapshot of it.
TEST(NextUpdateBoxes, AWorldUpdatesACarMovedBetweenUpdatesFromWhereItWasPut) {
    auto statics = std::make_shared<StaticWorld>();
    statics->add(std::make_shared<StaticCollider>(test::flat_grid(60.0, 30)));
    World world(statics);
    const CarSpec spec = CarSpec::default_car();
    world.add_car(spec, rolling(-10.0));
    world.add_car(spec, rolling(10.0));
    for (int k = 0; k < 5; ++k) world.update();

    RigidBodyState moved = world.car(0).state();
    moved.position.z -= 4.0;
    world.car(0).set_state(moved);
    const Aabb expected = detail::car_update_box(world.car(0), world.settings());
    World restored(statics);
    restored.add_car(spec, rolling(-10.0));
    restored.add_car(spec, rolling(10.0));
    restored.restore_state(world.save_state());

    world.update();
    restored.update();
    BoxLog log;
    world.debug_draw(log, {.update_boxes = true});
    ASSERT_EQ(log.boxes.size(), 2u);
    EXPECT_TRUE(same_bits(log.boxes[0], expected));
    EXPECT_EQ(world.state_hash(), restored.state_hash());
}

}  // namespace
}  // namespace trackphys
