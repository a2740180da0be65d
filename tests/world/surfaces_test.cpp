// Surfaces (docs/design.md#surfaces): the triangles' ids reach the contact, the world's table
// sets each wheel's grip from them, and bad tables or ids are refused by name.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

#include "support/error_message.hpp"
#include "trackphys/error.hpp"
#include "trackphys/track/track.hpp"
#include "trackphys/world/spawn.hpp"
#include "trackphys/world/world.hpp"
#include "world/world_scenes.hpp"

namespace trackphys {
namespace {

// A straight road along +Z whose triangles past z = 20 m are surface 1 (the patch).
TriangleMesh road_with_patch() {
    TriangleMesh mesh = test::straight_road(600.0, 20.0, 5.0);
    mesh.surfaces.resize(mesh.triangles.size());
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
        const auto& tri = mesh.triangles[t];
        const double z =
            (mesh.vertices[tri[0]].z + mesh.vertices[tri[1]].z + mesh.vertices[tri[2]].z) / 3.0;
        mesh.surfaces[t] = z > 20.0 ? SurfaceId{1} : SurfaceId{0};
    }
    return mesh;
}

World world_on(const TriangleMesh& mesh, std::vector<Surface> surfaces) {
    WorldSettings settings;
    settings.surfaces = std::move(surfaces);
    settings.threads = 1;
    return World(test::static_world_of(mesh), settings);
}

// The car rolls onto the patch at 20 m/s and brakes fully from z = 30 m; the metres it takes
// to stop (or 1000 when it has not stopped after 30 s).
double braking_distance(std::string_view preset, double patch_grip) {
    World world = world_on(road_with_patch(), {Surface{1.0}, Surface{patch_grip}});
    const CarSpec spec = CarSpec::preset(preset);
    RigidBodyState start = place_car_on_surface(world.statics(), spec, {0.0, 20.0, 30.0},
                                                glm::dquat(1.0, 0.0, 0.0, 0.0));
    world.add_car(spec, start);
    start.linear_velocity = {0.0, 0.0, 20.0};
    world.teleport_car(0, start);  // a vehicle model rolls at the new speed
    world.car(0).set_inputs({0.0, 1.0, 0.0});
    for (int i = 0; i < 3000; ++i) {
        world.update();
        if (world.car(0).speed() < 0.1) return world.car(0).state().position.z - start.position.z;
    }
    return 1000.0;
}

TEST(Surfaces, AnIcePatchLengthensBrakingForTheArcadeCarAndAVehicle) {
    for (const std::string_view preset : {"arcade", "gt"}) {
        const double dry = braking_distance(preset, 1.0);
        const double ice = braking_distance(preset, 0.1);
        RecordProperty(std::string(preset) + "_dry_m", std::to_string(dry));
        RecordProperty(std::string(preset) + "_ice_m", std::to_string(ice));
        // About v^2 / (2 mu g): 20 m on the dry road, ten times that on ice.
        EXPECT_LT(dry, 60.0) << preset;
        EXPECT_GT(ice, 4.0 * dry) << preset << ": dry " << dry << " m, ice " << ice << " m";
    }
}

// The arcade car rolling at 15 m/s on a flat square of one surface, steered fully left with
// neither throttle nor brake: its wheels' sideways friction alone bends and slows it, so the
// mean horizontal acceleration over 1.5 s is bounded by the surface's share of mu g. Braking
// (above) is bounded by the traction limit; this is the friction.
double mean_turning_acceleration(double grip) {
    TriangleMesh square = test::flat_grid(400.0, 40);
    square.surfaces.assign(square.triangles.size(), SurfaceId{1});
    World world = world_on(square, {Surface{1.0}, Surface{grip}});
    const CarSpec spec = CarSpec::preset("arcade");
    RigidBodyState start = place_car_on_surface(world.statics(), spec, {0.0, 5.0, 0.0},
                                                glm::dquat(1.0, 0.0, 0.0, 0.0));
    world.add_car(spec, start);
    start.linear_velocity = {0.0, 0.0, 15.0};
    world.teleport_car(0, start);
    world.car(0).set_inputs({0.0, 0.0, 1.0});
    const auto horizontal = [&] {
        const glm::dvec3 v = world.car(0).state().linear_velocity;
        return glm::dvec3(v.x, 0.0, v.z);
    };
    double sum = 0.0;
    const int updates = 150;
    for (int i = 0; i < updates; ++i) {
        const glm::dvec3 before = horizontal();
        world.update();
        sum += glm::length(horizontal() - before) / world.settings().dt_update;
    }
    return sum / updates;
}

TEST(Surfaces, ALowGripSurfaceBoundsTheArcadeCarsCornering) {
    const CarSpec spec = CarSpec::preset("arcade");
    const double g = 9.81;
    const double mu = spec.wheel_contact.friction * std::max(1.0, spec.rear_grip_factor);
    const double dry = mean_turning_acceleration(1.0);
    const double ice = mean_turning_acceleration(0.25);
    RecordProperty("dry_m_s2", std::to_string(dry));
    RecordProperty("ice_m_s2", std::to_string(ice));
    EXPECT_LT(ice, 0.25 * mu * g * 1.1) << "dry " << dry;
    EXPECT_GT(dry, 2.0 * ice) << "ice " << ice;
}

// A table of ones drives exactly as no table: grip 1 leaves every force's bits.
TEST(Surfaces, ATableOfOnesGivesTheSameStatesAsNoTable) {
    const auto hash_after = [](std::vector<Surface> surfaces) {
        World world = world_on(road_with_patch(), std::move(surfaces));
        for (const std::string_view preset : {"arcade", "gt"}) {
            const CarSpec spec = CarSpec::preset(preset);
            const double x = preset == "gt" ? 5.0 : -5.0;
            world.add_car(spec, place_car_on_surface(world.statics(), spec, {x, 20.0, 10.0},
                                                     glm::dquat(1.0, 0.0, 0.0, 0.0)));
            world.car(world.car_count() - 1).set_inputs({1.0, 0.0, 0.2});
        }
        for (int i = 0; i < 300; ++i) world.update();
        return world.state_hash();
    };
    EXPECT_EQ(hash_after({}), hash_after({Surface{1.0}, Surface{1.0}}));
    EXPECT_NE(hash_after({}), hash_after({Surface{1.0}, Surface{0.5}}));
}

// Each wheel reports the triangle of its deepest contact and its surface; a body ellipsoid
// above the road touches nothing.
TEST(Surfaces, ContactSurfaceNamesTheDeepestTriangleAndItsSurface) {
    const TriangleMesh mesh = road_with_patch();
    World world = world_on(mesh, {});
    const CarSpec spec = CarSpec::preset("arcade");
    for (const double z : {5.0, 100.0}) {
        world.add_car(spec, place_car_on_surface(world.statics(), spec, {0.0, 20.0, z},
                                                 glm::dquat(1.0, 0.0, 0.0, 0.0)));
    }
    for (int i = 0; i < 50; ++i) world.update();
    for (std::size_t car = 0; car < 2; ++car) {
        const SurfaceId expected = car == 0 ? 0 : 1;
        for (std::size_t k = 0; k < spec.ellipsoids.size(); ++k) {
            const std::optional<ContactSurface> touched = world.contact_surface(car, k);
            if (spec.ellipsoids[k].role == EllipsoidRole::body) {
                EXPECT_FALSE(touched.has_value()) << "car " << car << " ellipsoid " << k;
                continue;
            }
            ASSERT_TRUE(touched.has_value()) << "car " << car << " wheel " << k;
            EXPECT_EQ(touched->triangle.collider, 0u);
            EXPECT_EQ(touched->surface, mesh.surfaces[touched->triangle.triangle]);
            EXPECT_EQ(touched->surface, expected) << "car " << car << " wheel " << k;
            EXPECT_EQ(touched->triangle, world.save_state().cars[car].deepest_refs[k]);
        }
    }
    const std::string past =
        test::error_of([&] { world.contact_surface(0, spec.ellipsoids.size()); });
    EXPECT_NE(past.find("has no ellipsoid"), std::string::npos) << past;
}

TEST(Surfaces, BadGripsAndIdsBeyondTheTableAreRefusedByName) {
    const TriangleMesh mesh = road_with_patch();
    for (const double grip : {0.0, -0.5, std::numeric_limits<double>::quiet_NaN(),
                              std::numeric_limits<double>::infinity(), 10.000001, 1000.0}) {
        const std::string why = test::error_of([&] { world_on(mesh, {Surface{}, Surface{grip}}); });
        EXPECT_NE(why.find("WorldSettings.surfaces[1].grip must be in (0, 10]"), std::string::npos)
            << grip << ": " << why;
    }
    EXPECT_NO_THROW(world_on(mesh, {Surface{}, Surface{max_surface_grip}}));
    const std::string short_table = test::error_of([&] { world_on(mesh, {Surface{0.8}}); });
    EXPECT_NE(short_table.find("collider 0's triangle "), std::string::npos) << short_table;
    EXPECT_NE(short_table.find(" is surface 1, beyond WorldSettings.surfaces (1 entries)"),
              std::string::npos)
        << short_table;
    // Without a table every id is the dry road.
    EXPECT_NO_THROW(world_on(mesh, {}));

    TriangleMesh wrong_count = mesh;
    wrong_count.surfaces.pop_back();
    const std::string count = test::error_of([&] { StaticCollider collider(wrong_count); });
    EXPECT_NE(count.find("surface ids for"), std::string::npos) << count;
}

// Where the mode lets a game add a collider after making the World, its ids are checked at
// the next update, before a sub-step could read the table past its end.
TEST(Surfaces, ALateColliderWithAnIdBeyondTheTableIsRefusedAtTheUpdate) {
    auto statics = std::make_shared<StaticWorld>();
    statics->add(std::make_shared<StaticCollider>(test::straight_road(600.0, 20.0, 5.0)));
    WorldSettings settings;
    settings.mid_phase = MidPhaseMode::none;
    settings.surfaces = {Surface{1.0}, Surface{0.5}};
    World world(statics, settings);
    const CarSpec spec = CarSpec::preset("arcade");
    world.add_car(spec, place_car_on_surface(world.statics(), spec, {0.0, 20.0, 30.0},
                                             glm::dquat(1.0, 0.0, 0.0, 0.0)));
    world.update();

    TriangleMesh late = road_with_patch();
    for (SurfaceId& id : late.surfaces) id = SurfaceId{40000};
    statics->add(std::make_shared<StaticCollider>(late));
    const std::uint64_t before = world.state_hash();
    const std::string why = test::error_of([&] { world.update(); });
    EXPECT_NE(why.find("collider 1's triangle 0 is surface 40000, beyond WorldSettings.surfaces"),
              std::string::npos)
        << why;
    EXPECT_EQ(world.state_hash(), before);
    // It stays refused: the colliders were not marked checked.
    EXPECT_THROW(world.update(), Error);
}

// The collider keeps the ids by mesh index, dropped triangles' too, and none for all zeros.
TEST(Surfaces, TheColliderKeepsTheIdsByMeshIndex) {
    TriangleMesh mesh;
    mesh.vertices = {{0, 0, 0}, {10, 0, 0}, {10, 0, 10}, {0, 0, 10}, {20, 0, 0}};
    mesh.triangles = {{0, 2, 1}, {0, 1, 4}, {0, 3, 2}};  // the second is degenerate
    mesh.surfaces = {4, 9, 2};
    const StaticCollider collider(mesh);
    EXPECT_EQ(collider.degenerate_count(), 1u);
    EXPECT_EQ(collider.surface(0), 4);
    EXPECT_EQ(collider.surface(1), 9);
    EXPECT_EQ(collider.surface(2), 2);
    EXPECT_EQ(collider.highest_surface(), 4);  // the dropped triangle does not count
    EXPECT_NE(test::error_of([&] { collider.surface(3); }).find("past the mesh's 3"),
              std::string::npos);
    mesh.surfaces = {0, 0, 0};
    EXPECT_TRUE(StaticCollider(mesh).surfaces().empty());
}

// The fingerprint a snapshot is tied to covers the ids: a map baked again with other
// materials is another world, while no ids and all zeros (stored alike) are the same.
TEST(Surfaces, TheContentHashTellsOtherSurfacesApart) {
    TriangleMesh mesh = road_with_patch();
    const std::uint64_t patched = StaticCollider(mesh).content_hash();
    mesh.surfaces.back() = SurfaceId{2};
    EXPECT_NE(StaticCollider(mesh).content_hash(), patched);
    mesh.surfaces.assign(mesh.triangles.size(), SurfaceId{0});
    const std::uint64_t zeros = StaticCollider(mesh).content_hash();
    EXPECT_NE(zeros, patched);
    mesh.surfaces.clear();
    EXPECT_EQ(StaticCollider(mesh).content_hash(), zeros);

    const auto world_with_a_car = [](const TriangleMesh& road) {
        World world = world_on(road, {Surface{1.0}, Surface{0.5}});
        const CarSpec spec = CarSpec::default_car();
        world.add_car(spec, place_car_on_surface(world.statics(), spec, {0.0, 20.0, 30.0},
                                                 glm::dquat(1.0, 0.0, 0.0, 0.0)));
        return world;
    };
    const World saved = world_with_a_car(road_with_patch());
    World relabelled = world_with_a_car(mesh);
    EXPECT_NE(
        test::error_of([&] { relabelled.restore_state(saved.save_state()); }).find("collider 0"),
        std::string::npos);
}

// The generated track labels its road and its walls.
TEST(Surfaces, TheTrackGeneratorLabelsRoadAndWalls) {
    const Track track = generate_track(TrackParams{});
    for (const TrackChunk& chunk : track.chunks) {
        ASSERT_EQ(chunk.mesh.surfaces.size(), chunk.mesh.triangles.size());
        for (std::size_t t = 0; t < chunk.mesh.triangles.size(); ++t)
            ASSERT_EQ(chunk.mesh.surfaces[t],
                      t < chunk.road_triangle_count ? kRoadSurface : kWallSurface);
    }
}

}  // namespace
}  // namespace trackphys
