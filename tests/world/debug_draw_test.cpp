// World::debug_draw: a DebugDraw sees exactly the cars' ellipsoid poses and the contacts
// World::contacts reports, car by car in the documented order; the optional callbacks run
// only when asked; and RecordingWriter::write_frame, which records through those callbacks,
// writes the line a hand-written frame of the same world would.
#include "trackphys/world/debug_draw.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <optional>
#include <set>
#include <span>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include <gtest/gtest.h>

#include "support/same_bits.hpp"
#include "tool_world_settings.hpp"
#include "trackphys/io/recording.hpp"
#include "trackphys/world/world.hpp"
#include "world/world_scenes.hpp"

namespace trackphys {
namespace {

// Every call, as it came.
struct CallLog final : DebugDraw {
    struct Event {
        char kind;  // 'c'ar, 'e'llipsoid, 'k' contact, 'b'ox, 'l'isted, 'p'assed the cull,
                    // 'x' contact between cars (car_a)
        std::size_t car;
    };
    std::vector<Event> events;
    std::vector<const Car*> cars;
    std::vector<DebugEllipsoid> ellipsoids;
    std::vector<DebugContact> contacts;
    std::vector<CarPairContact> car_contacts;
    std::vector<Aabb> boxes;
    std::vector<DebugTriangle> listed;
    std::vector<DebugTriangle> kept;
    std::vector<double> kept_bounds;

    void draw_car(std::size_t index, const Car& car) override {
        events.push_back({'c', index});
        cars.push_back(&car);
    }
    void draw_ellipsoid(const DebugEllipsoid& e) override {
        events.push_back({'e', e.car});
        ellipsoids.push_back(e);
    }
    void draw_contact(const DebugContact& c) override {
        events.push_back({'k', c.car});
        contacts.push_back(c);
    }
    void draw_car_contact(const CarPairContact& c) override {
        events.push_back({'x', c.car_a});
        car_contacts.push_back(c);
    }
    void draw_update_box(std::size_t car, const Aabb& box) override {
        events.push_back({'b', car});
        boxes.push_back(box);
    }
    void draw_listed_triangle(const DebugTriangle& t) override {
        events.push_back({'l', t.car});
        listed.push_back(t);
    }
    void draw_kept_triangle(const DebugTriangle& t, double depth_bound) override {
        events.push_back({'p', t.car});
        kept.push_back(t);
        kept_bounds.push_back(depth_bound);
    }
};

using test::same_bits;

// Three default cars on flat ground, rolling towards a wall at different speeds: wheels on
// the road from the start, the fastest car's body against the wall within half a second.
// With `only`, that car alone.
World three_cars(std::optional<int> only = std::nullopt) {
    auto statics = std::make_shared<StaticWorld>();
    statics->add(std::make_shared<StaticCollider>(test::flat_grid(60.0, 30)));
    statics->add(std::make_shared<StaticCollider>(test::wall(6.0, 60.0, 3.0)));
    World world(statics, cli::tool_world_settings());
    const CarSpec spec = CarSpec::default_car();
    for (int k = 0; k < 3; ++k) {
        if (only && k != *only) continue;
        RigidBodyState state;
        state.position = {-10.0 + 10.0 * k, spec.lowest_point_depth() + 0.001, 0.0};
        state.linear_velocity = {0.0, 0.0, 5.0 * (k + 1)};
        world.car(world.add_car(spec, state)).set_inputs({0.5, 0.0, 0.3 * (k - 1)});
    }
    return world;
}

// The log of one update holds every car once, in order, each with exactly its ellipsoids
// (bit for bit what Car::world_ellipsoid gives) and exactly the overlapping contacts of
// World::contacts; adds how many contacts it held to `contacts`.
void expect_cars_and_contacts(const World& world, const CallLog& log, std::size_t& contacts) {
    std::size_t expected_events = 0;
    EXPECT_EQ(log.cars.size(), world.car_count());
    std::size_t e = 0, c = 0, event = 0;
    for (std::size_t k = 0; k < world.car_count() && k < log.cars.size(); ++k) {
        const Car& car = world.car(k);
        EXPECT_EQ(log.cars[k], &car);
        ASSERT_LE(event + 1 + car.ellipsoid_count(), log.events.size());
        EXPECT_EQ(log.events[event].kind, 'c');
        EXPECT_EQ(log.events[event++].car, k);
        for (std::size_t i = 0; i < car.ellipsoid_count(); ++i, ++e, ++event) {
            ASSERT_LT(e, log.ellipsoids.size());
            const DebugEllipsoid& drawn = log.ellipsoids[e];
            const Ellipsoid placed = car.world_ellipsoid(i);
            EXPECT_EQ(log.events[event].kind, 'e');
            EXPECT_EQ(drawn.car, k);
            EXPECT_EQ(drawn.ellipsoid, i);
            EXPECT_TRUE(same_bits(drawn.shape.center(), placed.center()))
                << "car " << k << " ellipsoid " << i;
            EXPECT_TRUE(same_bits(drawn.shape.orientation(), placed.orientation()));
            EXPECT_TRUE(same_bits(drawn.shape.semi_axes(), placed.semi_axes()));
            EXPECT_EQ(drawn.role, car.spec().ellipsoids[i].role);
            EXPECT_EQ(drawn.suspension, car.suspension(i));
        }
        const std::span<const Contact> reported = world.contacts(k);
        for (std::size_t i = 0; i < reported.size(); ++i) {
            if (!(reported[i].depth > 0.0)) continue;
            ASSERT_LT(c, log.contacts.size())
                << "car " << k << " ellipsoid " << i << "'s contact is missing";
            const DebugContact& drawn = log.contacts[c++];
            ASSERT_LT(event, log.events.size());
            EXPECT_EQ(log.events[event++].kind, 'k');
            EXPECT_EQ(drawn.car, k);
            EXPECT_EQ(drawn.ellipsoid, i);
            EXPECT_TRUE(same_bits(drawn.contact, reported[i])) << "car " << k << " ellipsoid " << i;
        }
        expected_events = event;
    }
    EXPECT_EQ(e, log.ellipsoids.size());
    EXPECT_EQ(c, log.contacts.size()) << "contacts that World::contacts does not report";
    EXPECT_EQ(log.events.size(), expected_events);
    contacts += c;
}

TEST(DebugDraw, ReportsExactlyTheEllipsoidsAndTheContactsOfWorldContacts) {
    World world = three_cars();
    std::size_t contacts = 0;
    std::set<std::size_t> touching_cars;
    for (int update = 0; update < 60; ++update) {
        world.update();
        CallLog log;
        world.debug_draw(log);
        expect_cars_and_contacts(world, log, contacts);
        for (const DebugContact& c : log.contacts) touching_cars.insert(c.car);
        if (HasFatalFailure()) return;
    }
    EXPECT_GT(contacts, 60u * 3u) << "the scene should keep wheels on the road";
    EXPECT_EQ(touching_cars.size(), 3u);
}

TEST(DebugDraw, BeforeTheFirstUpdateShowsCarsButNoContactsNorLists) {
    World world = three_cars();
    CallLog log;
    world.debug_draw(log, DebugDrawOptions::all());
    std::size_t contacts = 0;
    expect_cars_and_contacts(world, log, contacts);
    EXPECT_EQ(contacts, 0u);
    EXPECT_TRUE(log.boxes.empty());
    EXPECT_TRUE(log.listed.empty());
    EXPECT_TRUE(log.kept.empty());
}

TEST(DebugDraw, OptionsOffCallNothingOfThem) {
    World world = three_cars();
    for (int update = 0; update < 5; ++update) world.update();

    CallLog defaults;
    world.debug_draw(defaults);
    EXPECT_FALSE(defaults.contacts.empty());
    EXPECT_TRUE(defaults.boxes.empty());
    EXPECT_TRUE(defaults.listed.empty());
    EXPECT_TRUE(defaults.kept.empty());

    CallLog none;
    world.debug_draw(none, {.cars = false,
                            .ellipsoids = false,
                            .contacts = false,
                            .car_contacts = false,
                            .update_boxes = false,
                            .listed_triangles = false,
                            .kept_triangles = false});
    EXPECT_TRUE(none.events.empty());

    CallLog only_kept;
    world.debug_draw(only_kept, {.cars = false,
                                 .ellipsoids = false,
                                 .contacts = false,
                                 .car_contacts = false,
                                 .update_boxes = false,
                                 .listed_triangles = false,
                                 .kept_triangles = true});
    EXPECT_FALSE(only_kept.kept.empty());
    EXPECT_EQ(only_kept.events.size(), only_kept.kept.size());
}

// The pipeline's lists as drawn, car by car: each car's update box holds the car, and its
// listed triangles meet that box (its queries' shapes lie in it: a triangle of another
// car's lists need not); the kept triangles are listed ones of the same car and ellipsoid,
// with a positive depth bound, each the collider's own triangle; an ellipsoid with a contact
// kept at least one.
void expect_the_pipelines_lists(const World& world, const CallLog& log) {
    ASSERT_EQ(log.boxes.size(), world.car_count());
    for (std::size_t k = 0; k < world.car_count(); ++k)
        EXPECT_TRUE(log.boxes[k].contains(world.car(k).state().position)) << "car " << k;
    const auto bounds = [](const DebugTriangle& t) {
        Aabb box;
        for (int v = 0; v < 3; ++v) box.expand(t.triangle[v]);
        return box;
    };
    std::set<std::tuple<std::size_t, std::size_t, TriangleRef>> listed;
    for (const DebugTriangle& t : log.listed) {
        listed.insert({t.car, t.ellipsoid, t.ref});
        EXPECT_TRUE(bounds(t).overlaps(log.boxes[t.car]))
            << "car " << t.car << " ellipsoid " << t.ellipsoid
            << " lists a triangle outside its box";
    }
    for (std::size_t j = 0; j < log.kept.size(); ++j) {
        const DebugTriangle& t = log.kept[j];
        EXPECT_TRUE(listed.contains({t.car, t.ellipsoid, t.ref})) << "kept but not listed";
        EXPECT_GT(log.kept_bounds[j], 0.0);
        const Triangle stored = world.statics().collider(t.ref.collider).triangle(t.ref.triangle);
        for (int v = 0; v < 3; ++v) EXPECT_TRUE(same_bits(t.triangle[v], stored[v]));
    }
    for (const DebugContact& c : log.contacts) {
        const bool on_kept = std::any_of(
            log.kept.begin(), log.kept.end(),
            [&](const DebugTriangle& t) { return t.car == c.car && t.ellipsoid == c.ellipsoid; });
        EXPECT_TRUE(on_kept) << "car " << c.car << " ellipsoid " << c.ellipsoid
                             << " has a contact but no kept triangle";
    }
}

TEST(DebugDraw, ListsThePipelinesTrianglesAndBoxes) {
    World world = three_cars();
    for (int update = 0; update < 5; ++update) world.update();
    CallLog log;
    world.debug_draw(log, DebugDrawOptions::all());
    ASSERT_FALSE(log.kept.empty());
    expect_the_pipelines_lists(world, log);
}

// The lists and survivors are a worker's scratch during an update, which the next car
// rewrites: each car's drawn triangles are its own, those a world of that car alone draws.
TEST(DebugDraw, ACarsTrianglesAreItsOwnWhicheverCarRanAfterIt) {
    World world = three_cars();
    std::vector<World> alone;
    for (int k = 0; k < 3; ++k) alone.push_back(three_cars(k));
    for (int update = 0; update < 20; ++update) {
        world.update();
        for (World& one : alone) one.update();
    }
    CallLog log;
    world.debug_draw(log, DebugDrawOptions::all());
    for (std::size_t k = 0; k < 3; ++k) {
        CallLog own;
        alone[k].debug_draw(own, DebugDrawOptions::all());
        const auto refs = [](const std::vector<DebugTriangle>& drawn, std::size_t car) {
            std::vector<std::pair<std::size_t, TriangleRef>> out;
            for (const DebugTriangle& t : drawn)
                if (t.car == car) out.push_back({t.ellipsoid, t.ref});
            return out;
        };
        EXPECT_FALSE(own.kept.empty()) << "car " << k;
        EXPECT_EQ(refs(log.listed, k), refs(own.listed, 0)) << "car " << k;
        EXPECT_EQ(refs(log.kept, k), refs(own.kept, 0)) << "car " << k;
    }
}

// Three default cars side by side on flat ground, 2.15 m apart (5 cm between their wheels),
// driving straight at different throttles: their update boxes overlap (each pads the car by
// broad_phase_margin), so they are one island of three, yet they never touch. With `only`,
// that car alone.
World side_by_side(std::optional<int> only = std::nullopt) {
    auto statics = std::make_shared<StaticWorld>();
    statics->add(std::make_shared<StaticCollider>(test::flat_grid(60.0, 30)));
    World world(statics, cli::tool_world_settings());
    const CarSpec spec = CarSpec::default_car();
    for (int k = 0; k < 3; ++k) {
        if (only && k != *only) continue;
        RigidBodyState state;
        state.position = {2.15 * (k - 1), spec.lowest_point_depth() + 0.001, -10.0};
        state.linear_velocity = {0.0, 0.0, 5.0};
        world.car(world.add_car(spec, state)).set_inputs({0.2 + 0.3 * k, 0.0, 0.0});
    }
    return world;
}

// A worker keeps one scratch per car of the island it updates (the k-th car's lists in the
// k-th): each car of an island draws its own lists and survivors, not another position's.
// The cars never touch, so nothing pushes and each car's lists are those of the car alone.
TEST(DebugDraw, EachCarOfAnIslandDrawsItsOwnLists) {
    World world = side_by_side();
    std::vector<World> alone;
    for (int k = 0; k < 3; ++k) alone.push_back(side_by_side(k));
    const auto refs = [](const std::vector<DebugTriangle>& drawn, std::size_t car) {
        std::vector<std::pair<std::size_t, TriangleRef>> out;
        for (const DebugTriangle& t : drawn)
            if (t.car == car) out.push_back({t.ellipsoid, t.ref});
        return out;
    };
    std::size_t kept[3] = {};
    for (int update = 0; update < 20; ++update) {
        world.update();
        for (World& one : alone) one.update();
        ASSERT_EQ(world.last_profile().car_pairs, 2u) << "update " << update << ": not one island";
        ASSERT_EQ(world.last_profile().car_contacts, 0u) << "update " << update;
        if (update < 5) continue;  // the wheels are on the road from here
        CallLog log;
        world.debug_draw(log, DebugDrawOptions::all());
        expect_the_pipelines_lists(world, log);
        for (std::size_t k = 0; k < 3; ++k) {
            CallLog own;
            alone[k].debug_draw(own, DebugDrawOptions::all());
            kept[k] += own.kept.size();
            EXPECT_EQ(refs(log.listed, k), refs(own.listed, 0))
                << "update " << update << " car " << k;
            EXPECT_EQ(refs(log.kept, k), refs(own.kept, 0)) << "update " << update << " car " << k;
        }
        if (HasFailure()) return;
    }
    for (std::size_t k = 0; k < 3; ++k) EXPECT_GT(kept[k], 0u) << "car " << k << " kept nothing";
}

std::string read_file(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

// The contacts between cars come after every car's calls, exactly World::car_contacts.
TEST(DebugDraw, ReportsTheContactsBetweenCarsAfterTheCars) {
    World world = test::one_car_pushing_a_braked_one();
    std::size_t drawn = 0;
    for (int update = 0; update < 300; ++update) {
        world.update();
        CallLog log;
        world.debug_draw(log);
        const std::span<const CarPairContact> expected = world.car_contacts();
        ASSERT_EQ(log.car_contacts.size(), expected.size());
        for (std::size_t i = 0; i < expected.size(); ++i) {
            const CarPairContact& c = log.car_contacts[i];
            EXPECT_EQ(std::tie(c.car_a, c.car_b, c.ellipsoid_a, c.ellipsoid_b),
                      std::tie(expected[i].car_a, expected[i].car_b, expected[i].ellipsoid_a,
                               expected[i].ellipsoid_b));
            EXPECT_TRUE(same_bits(c.contact, expected[i].contact));
        }
        const auto first_pair = std::find_if(log.events.begin(), log.events.end(),
                                             [](const CallLog::Event& e) { return e.kind == 'x'; });
        EXPECT_TRUE(std::all_of(first_pair, log.events.end(), [](const CallLog::Event& e) {
            return e.kind == 'x';
        })) << "a car's call after the contacts between cars";
        drawn += expected.size();
    }
    EXPECT_GT(drawn, 0u) << "the cars never touched: the test would prove little";
}

// write_frame records through the DebugDraw callbacks; the line must be the one written by
// hand from the same world, byte for byte, laps and contacts between cars included.
void expect_recorded_as_by_hand(World world, int updates,
                                const std::vector<std::optional<int>>& laps,
                                const std::string& must_hold) {
    RecordingHeader header;
    header.car_ellipsoids.assign(world.car_count(), CarSpec::default_car().ellipsoids);
    const std::filesystem::path folder = std::filesystem::temp_directory_path();
    const std::filesystem::path drawn_file = folder / "trackphys_debug_draw_drawn.jsonl";
    const std::filesystem::path by_hand_file = folder / "trackphys_debug_draw_by_hand.jsonl";
    {
        RecordingWriter drawn(drawn_file, header);
        RecordingWriter by_hand(by_hand_file, header);
        for (int update = 0; update < updates; ++update) {
            world.update();
            drawn.write_frame(world, laps);
            by_hand.begin_frame(world.time(), world.state_hash(),
                                world.settings().profile
                                    ? std::optional(world.last_profile().update_us)
                                    : std::nullopt);
            for (std::size_t k = 0; k < world.car_count(); ++k) {
                const Car& car = world.car(k);
                by_hand.add_car({car.state().position, car.state().orientation, car.speed(),
                                 car.suspension(), world.contacts(k), car.inputs(),
                                 k < laps.size() ? laps[k] : std::nullopt,
                                 std::nullopt});  // arcade cars: no vehicle model
            }
            by_hand.end_frame(world.car_contacts());
        }
        drawn.finish();
        by_hand.finish();
    }
    const std::string drawn = read_file(drawn_file), by_hand = read_file(by_hand_file);
    std::filesystem::remove(drawn_file);
    std::filesystem::remove(by_hand_file);
    EXPECT_NE(drawn.find(must_hold), std::string::npos) << "no " << must_hold << " recorded";
    EXPECT_EQ(drawn, by_hand);
}

TEST(DebugDraw, RecordingWriterWritesTheLineOfAHandWrittenFrame) {
    expect_recorded_as_by_hand(three_cars(), 40, {2, std::nullopt, 0}, "\"contacts\":[[");
    expect_recorded_as_by_hand(test::one_car_pushing_a_braked_one(), 300, {},
                               "\"car_contacts\":[[");
}

}  // namespace
}  // namespace trackphys
