// World::save_state / restore_state: bit-identical continuation on the default track with
// the autopilot, into the same world and into a fresh one, and snapshots of other worlds,
// other cars or invalid states rejected without changing anything.
#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "support/error_message.hpp"
#include "trackphys/error.hpp"
#include "trackphys/io/snapshot_file.hpp"
#include "trackphys/world/autopilot.hpp"
#include "trackphys/world/race_grid.hpp"
#include "trackphys/world/world.hpp"
#include "world/track_world.hpp"
#include "world/world_scenes.hpp"

namespace trackphys {
namespace {

using test::error_of;

using test::default_track;
using test::on_start_line;

// One car on the default track driven by the autopilot: the drive command's loop.
struct Drive {
    World world;
    Autopilot pilot;

    Drive()
        : world(default_track().statics, WorldSettings{}, default_track().trees),
          pilot(default_track().track, CarSpec::default_car()) {
        world.add_car(CarSpec::default_car(), on_start_line(default_track().track));
    }
    void step() {
        Car& car = world.car(0);
        car.set_inputs(pilot.drive(car));
        world.update();
        pilot.locate(car);
    }
    // The state hash after each of n updates.
    std::vector<std::uint64_t> run(int n) {
        std::vector<std::uint64_t> hashes;
        for (int i = 0; i < n; ++i) {
            step();
            hashes.push_back(world.state_hash());
        }
        return hashes;
    }
};

TEST(WorldSnapshot, RestoreThenUpdateIsBitIdentical) {
    Drive original;
    original.run(250);  // up to speed, into the first turns
    const WorldSnapshot saved = original.world.save_state();
    const AutopilotProgress progress = original.pilot.progress();
    const std::vector<std::uint64_t> expected = original.run(400);
    const std::string expected_end = encode_snapshot(original.world.save_state());

    // Into a freshly constructed world (its car added at the start line, then restored).
    Drive fresh;
    fresh.world.restore_state(saved);
    fresh.pilot.set_progress(progress);
    EXPECT_EQ(fresh.world.update_count(), 250u);
    EXPECT_EQ(fresh.world.time(), 2.5);
    EXPECT_EQ(fresh.run(400), expected);
    // Not only the hashed state: contacts, exact-test hints and resets too.
    EXPECT_EQ(encode_snapshot(fresh.world.save_state()), expected_end);

    // Into the same world, which has moved on since: the same again.
    original.world.restore_state(saved);
    original.pilot.set_progress(progress);
    EXPECT_EQ(original.run(400), expected);

    // Through a file.
    const SnapshotFile loaded = decode_snapshot(encode_snapshot(saved));
    Drive from_file;
    from_file.world.restore_state(loaded.world);
    from_file.pilot.set_progress(progress);
    EXPECT_EQ(from_file.run(400), expected);

    // Saved and restored before every update: restoring a live state changes no bit.
    Drive cycled;
    cycled.world.restore_state(saved);
    cycled.pilot.set_progress(progress);
    for (const std::uint64_t hash : expected) {
        cycled.world.restore_state(cycled.world.save_state());
        cycled.step();
        ASSERT_EQ(cycled.world.state_hash(), hash) << "update " << cycled.world.update_count();
    }
}

// A field of 12 cars from the grid, at full throttle on scripted steering: a snapshot taken
// after each of the first 40 updates, restored into a world that never ran (its cars just
// added), gives the saved world's next update to the bit, its contacts and hints included.
// Each car's memory of which mid-phase lists were empty sets how far its next query looks
// ahead, so what its exact tests meet: before snapshots kept it, the restore after update 5
// gave car 7 a contact 0.037 m apart where the saved world had none.
TEST(WorldSnapshot, RestoreIntoAWorldThatNeverRanIsBitIdenticalAtEveryUpdate) {
    const test::TrackWorld& tw = test::default_track();
    const CarSpec spec = CarSpec::default_car();
    const std::vector<RigidBodyState> grid = race_grid(tw.track, *tw.statics, spec, 12);
    const auto field = [&] {
        auto world = std::make_unique<World>(tw.statics, WorldSettings{}, tw.trees);
        for (const RigidBodyState& start : grid) world->add_car(spec, start);
        return world;
    };
    const auto update = [](World& world) {
        const auto u = static_cast<double>(world.update_count());
        for (std::size_t i = 0; i < world.car_count(); ++i)
            world.car(i).set_inputs(
                {.throttle = 1.0, .brake = 0.0, .steer = 0.25 * std::sin(0.07 * u + double(i))});
        world.update();
    };
    const std::unique_ptr<World> original = field();
    for (int k = 0; k < 40; ++k) {
        const std::unique_ptr<World> restored = field();
        restored->restore_state(original->save_state());
        update(*original);
        update(*restored);
        ASSERT_EQ(restored->state_hash(), original->state_hash()) << "restored after " << k;
        // Not ASSERT_EQ: a failure would print both encodings, some 40 kB each.
        ASSERT_TRUE(encode_snapshot(restored->save_state()) ==
                    encode_snapshot(original->save_state()))
            << "restored after " << k;
    }
}

// Statics far smaller than the track, for the rejection cases.
struct SmallWorld {
    std::shared_ptr<const StaticWorld> statics = test::static_world_of(test::flat_grid(40.0, 8));
    World world{statics};
    SmallWorld() {
        RigidBodyState start;
        start.position = {0.0, 0.52, 0.0};
        world.add_car(CarSpec::default_car(), start);
        for (int i = 0; i < 20; ++i) world.update();
    }
};

TEST(WorldSnapshot, AnotherWorldIsRejectedNamingWhatDiffers) {
    SmallWorld a;
    const WorldSnapshot saved = a.world.save_state();

    // Another collider: one vertex moved by a millimetre.
    TriangleMesh moved = test::flat_grid(40.0, 8);
    moved.vertices[3].y += 0.001;
    World other_mesh(test::static_world_of(moved));
    other_mesh.add_car(CarSpec::default_car(), a.world.car(0).state());
    EXPECT_NE(error_of([&] { other_mesh.restore_state(saved); }).find("collider 0 differs"),
              std::string::npos);

    // Another number of colliders.
    auto two = std::make_shared<StaticWorld>();
    two->add(std::make_shared<StaticCollider>(test::flat_grid(40.0, 8)));
    two->add(std::make_shared<StaticCollider>(test::wall(15.0, 10.0, 2.0)));
    World two_colliders(two);
    two_colliders.add_car(CarSpec::default_car(), a.world.car(0).state());
    EXPECT_NE(error_of([&] {
                  two_colliders.restore_state(saved);
              }).find("made over 1 colliders, this world has 2"),
              std::string::npos);

    // Another car spec.
    CarSpec heavier = CarSpec::default_car();
    heavier.mass.mass += 1.0;
    World other_car(a.statics);
    other_car.add_car(heavier, a.world.car(0).state());
    EXPECT_NE(error_of([&] { other_car.restore_state(saved); }).find("car 0 has another CarSpec"),
              std::string::npos);

    // Another number of cars.
    World no_car(a.statics);
    EXPECT_NE(error_of([&] {
                  no_car.restore_state(saved);
              }).find("the snapshot has 1 cars, this world 0"),
              std::string::npos);

    // Other settings.
    WorldSettings finer;
    finer.substeps = 5;
    World other_settings(a.statics, finer);
    other_settings.add_car(CarSpec::default_car(), a.world.car(0).state());
    EXPECT_NE(error_of([&] { other_settings.restore_state(saved); }).find("substeps 4 vs 5"),
              std::string::npos);
}

TEST(WorldSnapshot, InvalidStatesAreRejectedAndChangeNothing) {
    SmallWorld a;
    const WorldSnapshot good = a.world.save_state();
    for (int i = 0; i < 5; ++i) a.world.update();
    const std::string before = encode_snapshot(a.world.save_state());

    const double nan = std::numeric_limits<double>::quiet_NaN();
    struct Case {
        const char* name;
        void (*spoil)(WorldSnapshot&, double nan);
        const char* message;
    };
    const Case cases[] = {
        {"NaN velocity", [](WorldSnapshot& s, double n) { s.cars[0].state.linear_velocity.x = n; },
         "linear_velocity is not finite"},
        {"over-speed",
         [](WorldSnapshot& s, double) {
             s.cars[0].state.linear_velocity = {0.0, 0.0, 600.0};
         },
         "above WorldSettings.max_car_speed"},
        {"not a unit quaternion",
         [](WorldSnapshot& s, double) { s.cars[0].state.orientation.w = 2.0; }, "unit quaternion"},
        {"NaN throttle", [](WorldSnapshot& s, double n) { s.cars[0].inputs.throttle = n; },
         "throttle"},
        {"steer out of range", [](WorldSnapshot& s, double) { s.cars[0].inputs.steer = 1.5; },
         "steer"},
        {"suspension beyond its travel",
         [](WorldSnapshot& s, double) { s.cars[0].suspension[0] = 0.5; }, "travel must be in"},
        {"suspension on a body ellipsoid",
         [](WorldSnapshot& s, double) { s.cars[0].suspension[7] = 0.01; }, "ellipsoid 7"},
        {"NaN contact", [](WorldSnapshot& s, double n) { s.cars[0].contacts[2].point.y = n; },
         "contact"},
        {"short list", [](WorldSnapshot& s, double) { s.cars[0].contacts.pop_back(); },
         "lists differ"},
        {"touching a triangle the world lacks",
         [](WorldSnapshot& s, double) {
             s.cars[0].contacts[0].depth = 0.01;
             s.cars[0].deepest_refs[0] = TriangleRef{0, 1u << 30};
         },
         "ellipsoid 0 touches triangle 1073741824 of collider 0, which this world does not have"},
        {"touching a collider the world lacks",
         [](WorldSnapshot& s, double) {
             s.cars[0].contacts[1].depth = 0.01;
             s.cars[0].deepest_refs[1] = TriangleRef{~0u, 0};
         },
         "ellipsoid 1 touches triangle 0 of collider 4294967295"},
        {"bad dt", [](WorldSnapshot& s, double) { s.settings.dt_update = -1.0; }, "dt_update"},
    };
    for (const Case& c : cases) {
        WorldSnapshot spoiled = good;
        c.spoil(spoiled, nan);
        const std::string message = error_of([&] { a.world.restore_state(spoiled); });
        EXPECT_NE(message.find(c.message), std::string::npos) << c.name << ": " << message;
        EXPECT_EQ(encode_snapshot(a.world.save_state()), before) << c.name << " changed the world";
    }
}

}  // namespace
}  // namespace trackphys
