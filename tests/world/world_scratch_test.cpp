// A worker places the ellipsoids of every car it updates, and lists and culls its triangles,
// in its own scratch (World's WorkerScratch): cars of different shapes, updated one after
// another, each drive as they would alone.
#include <cmath>
#include <cstdint>
#include <cstring>
#include <memory>
#include <vector>

#include <gtest/gtest.h>

#include "trackphys/world/spawn.hpp"
#include "trackphys/world/world.hpp"
#include "world/world_scenes.hpp"

namespace trackphys {
namespace {

bool same_bits(const RigidBodyState& a, const RigidBodyState& b) {
    return std::memcmp(&a.position, &b.position, sizeof a.position) == 0 &&
           std::memcmp(&a.orientation, &b.orientation, sizeof a.orientation) == 0 &&
           std::memcmp(&a.linear_velocity, &b.linear_velocity, sizeof a.linear_velocity) == 0 &&
           std::memcmp(&a.angular_velocity, &b.angular_velocity, sizeof a.angular_velocity) == 0;
}

TEST(WorldScratch, CarsOfOtherShapesOnOneWorkerDriveAsAlone) {
    const auto ground = test::static_world_of(test::flat_grid(200.0, 50));
    // The default car, the same on taller wheels, and the formula car.
    CarSpec taller = CarSpec::default_car();
    for (CarEllipsoid& e : taller.ellipsoids)
        if (e.role != EllipsoidRole::body) e.semi_axes *= glm::dvec3(1.0, 1.2, 1.2);
    const std::vector<CarSpec> specs = {CarSpec::default_car(), taller, CarSpec::preset("formula")};
    WorldSettings one_worker;
    one_worker.threads = 1;
    // Far apart (each car an island of its own), so only the worker's sets are shared.
    const auto start = [&](std::size_t k) {
        const glm::dvec3 where(-50.0 + 50.0 * static_cast<double>(k), 0.5, 0.0);
        return place_car_on_surface(*ground, specs[k], where, glm::dquat(1.0, 0.0, 0.0, 0.0));
    };
    const CarInputs inputs{.throttle = 0.6, .brake = 0.0, .steer = 0.3};

    World together(ground, one_worker);
    std::vector<World> alone;
    for (std::size_t k = 0; k < specs.size(); ++k) {
        together.add_car(specs[k], start(k));
        together.car(k).set_inputs(inputs);
        alone.emplace_back(ground, one_worker);
        alone[k].add_car(specs[k], start(k));
        alone[k].car(0).set_inputs(inputs);
    }
    for (int update = 0; update < 60; ++update) {
        together.update();
        for (World& world : alone) world.update();
    }
    for (std::size_t k = 0; k < specs.size(); ++k) {
        EXPECT_GT(together.contacts(k)[1].depth, 0.0) << "car " << k << " left the ground";
        EXPECT_TRUE(same_bits(together.car(k).state(), alone[k].car(0).state())) << "car " << k;
    }
}

// Two cars on one worker, the first on the road at `on_road` and the second `offset` from
// it, driven with `inputs` (none: the cars' defaults), query as often in one world as the
// two do alone, update by update, and the second ends in the bits it reaches alone. With
// `one_island` they must step as one island of cars that never touch, and the first must
// end as alone too. Returns the queries counted.
std::size_t expect_queries_as_alone(glm::dvec3 on_road_at, glm::dvec3 offset,
                                    const CarInputs* inputs, bool one_island) {
    const auto ground = test::static_world_of(test::flat_grid(200.0, 50));
    const CarSpec spec = CarSpec::default_car();
    WorldSettings one_worker;
    one_worker.threads = 1;
    const RigidBodyState on_road =
        place_car_on_surface(*ground, spec, on_road_at, glm::dquat(1.0, 0.0, 0.0, 0.0));
    RigidBodyState other = on_road;
    other.position += offset;
    World together(ground, one_worker), first(ground, one_worker), second(ground, one_worker);
    together.add_car(spec, on_road);
    together.add_car(spec, other);
    first.add_car(spec, on_road);
    second.add_car(spec, other);
    if (inputs != nullptr)
        for (World* world : {&together, &first, &second})
            for (std::size_t i = 0; i < world->car_count(); ++i) world->car(i).set_inputs(*inputs);
    std::size_t queries = 0;
    for (int update = 0; update < 60; ++update) {
        together.update();
        first.update();
        second.update();
        if (one_island) {
            EXPECT_EQ(together.last_profile().car_pairs, 1u)
                << "update " << update << ": no island";
            EXPECT_EQ(together.last_profile().car_contacts, 0u) << "update " << update;
        }
        const std::size_t alone =
            first.last_profile().mid_queries + second.last_profile().mid_queries;
        EXPECT_EQ(together.last_profile().mid_queries, alone) << "update " << update;
        queries += alone;
    }
    if (one_island) {
        EXPECT_TRUE(same_bits(together.car(0).state(), first.car(0).state()));
    }
    EXPECT_TRUE(same_bits(together.car(1).state(), second.car(0).state()));
    EXPECT_TRUE(std::isfinite(together.contacts(1)[0].depth)) << "the falling car never landed";
    return queries;
}

// The look-ahead lists are the worker's too, but each car's queries look as far ahead as its
// own last lists say (an empty one to the end of the update), not the previous car's: a car
// falling from above the road (every list empty) after one on it, on one worker, queries as
// often as the two do alone.
TEST(WorldScratch, EachCarsQueriesLookAsFarAheadAsItsOwnLastLists) {
    EXPECT_GT(expect_queries_as_alone(glm::dvec3(-50.0, 0.5, 0.0), glm::dvec3(100.0, 1.5, 0.0),
                                      nullptr, false),
              0u);
}

// The same in an island of two: a car on the road and, beside it, one falling from 0.5 m
// higher, 2.15 m apart (5 cm between their wheels, inside the update boxes' margins), so
// one island whose cars never touch: nothing pushes, and each car drives and queries as it
// does alone. The falling car is the island's second, its lists the worker's second set
// (WorkerScratch::cars[1]): the empty bits it keeps for its next update must be its own,
// not the first set's (the road car's wheels list the road while the falling car's lists
// are still empty). The bits change no state, only how far the queries look ahead, so the
// query count is what shows them.
TEST(WorldScratch, EachCarOfAnIslandQueriesAsFarAheadAsItsOwnLastLists) {
    const CarInputs inputs{.throttle = 0.5, .brake = 0.0, .steer = 0.0};
    EXPECT_GT(expect_queries_as_alone(glm::dvec3(-1.075, 0.5, 0.0), glm::dvec3(2.15, 0.5, 0.0),
                                      &inputs, true),
              0u);
}

// A worker's sets are made for the whole field when it changes: cars added after the first
// update and packed into one island larger than the field was drive as in a world whose
// sets covered them from the start (four parked cars, far away, islands of their own).
TEST(WorldScratch, CarsAddedAfterTheFirstUpdateDriveAsInAFieldThatHadThem) {
    const auto ground = test::static_world_of(test::flat_grid(200.0, 50));
    const CarSpec spec = CarSpec::default_car();
    WorldSettings one_worker;
    one_worker.threads = 1;
    const auto at = [&](double x, double z) {
        return place_car_on_surface(*ground, spec, glm::dvec3(x, 0.5, z),
                                    glm::dquat(1.0, 0.0, 0.0, 0.0));
    };
    World grown(ground, one_worker), reference(ground, one_worker);
    grown.add_car(spec, at(0.0, 0.0));
    reference.add_car(spec, at(0.0, 0.0));
    for (int k = 0; k < 4; ++k) reference.add_car(spec, at(-80.0, -80.0 + 12.0 * k));
    grown.update();
    reference.update();
    // Side by side, 2.3 m apart: one island of four.
    const std::size_t in_reference[4] = {0, 5, 6, 7};
    for (int k = 1; k < 4; ++k) {
        grown.add_car(spec, at(2.3 * k, 0.0));
        reference.add_car(spec, at(2.3 * k, 0.0));
    }
    const CarInputs inputs{.throttle = 0.5, .brake = 0.0, .steer = 0.2};
    for (std::size_t k = 0; k < 4; ++k) {
        grown.car(k).set_inputs(inputs);
        reference.car(in_reference[k]).set_inputs(inputs);
    }
    std::uint64_t pairs = 0;
    for (int update = 0; update < 60; ++update) {
        grown.update();
        reference.update();
        pairs += grown.last_profile().car_pairs;
    }
    EXPECT_GT(pairs, 0u) << "the four cars never formed an island";
    for (std::size_t k = 0; k < 4; ++k)
        EXPECT_TRUE(same_bits(grown.car(k).state(), reference.car(in_reference[k]).state()))
            << "car " << k;
}

}  // namespace
}  // namespace trackphys
