// place_car_on_surface: a car placed from any point above a road rests on it, every
// ellipsoid clear (so World::add_car takes it) and one touching (not floating above), on
// made-up scenes with a kerb, a wall and nothing, on the generated track and on four real
// tracks.

#include "trackphys/world/spawn.hpp"

#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "support/error_message.hpp"
#include "support/real_tracks.hpp"
#include "trackphys/dynamics/car.hpp"
#include "trackphys/geometry/contact.hpp"
#include "trackphys/world/world.hpp"
#include "world/track_world.hpp"
#include "world/world_scenes.hpp"

namespace trackphys {
namespace {

constexpr double kClearance = 0.001;  // place_car_on_surface's default
constexpr double kTolerance = 1e-4;   // its bisection's

glm::dquat heading(double radians) { return glm::angleAxis(radians, glm::dvec3(0.0, 1.0, 0.0)); }

// How close the placed car's ellipsoids come to the statics: the deepest signed contact
// over every triangle within 1 m of any of them (-infinity when there is none).
double deepest_contact(const StaticWorld& statics, const CarSpec& spec,
                       const RigidBodyState& state) {
    const Car car(spec, state);
    double deepest = -std::numeric_limits<double>::infinity();
    std::vector<TriangleRef> refs;
    for (std::size_t i = 0; i < car.ellipsoid_count(); ++i) {
        const Ellipsoid e = car.world_ellipsoid(i);
        refs.clear();
        statics.query_aabb(e.bounds().padded(1.0), refs);
        for (const TriangleRef& ref : refs)
            deepest = std::max(
                deepest,
                ellipsoid_triangle_contact(e, statics.collider(ref.collider).triangle(ref.triangle))
                    .depth);
    }
    return deepest;
}

// The car placed from `spawn` rests: clear of everything by the clearance, touching
// something within the bisection's tolerance, straight above or below the spawn point,
// upright as asked, and World::add_car takes it.
::testing::AssertionResult rests(const std::shared_ptr<const StaticWorld>& statics,
                                 const CarSpec& spec, const glm::dvec3& spawn,
                                 const glm::dquat& orientation,
                                 RigidBodyState* placed_out = nullptr) {
    RigidBodyState placed;
    try {
        placed = place_car_on_surface(*statics, spec, spawn, orientation);
    } catch (const Error& e) {
        return ::testing::AssertionFailure() << e.what();
    }
    if (placed_out) *placed_out = placed;
    const double deepest = deepest_contact(*statics, spec, placed);
    if (placed.position.x != spawn.x || placed.position.z != spawn.z ||
        !(glm::dot(placed.orientation, orientation) >= 1.0 - 1e-12))
        return ::testing::AssertionFailure() << "moved other than along +Y";
    if (!(deepest <= -kClearance + 1e-12 && deepest >= -kClearance - kTolerance - 1e-12))
        return ::testing::AssertionFailure()
               << "deepest contact " << deepest << " m at height " << placed.position.y
               << ": not resting " << kClearance << " m clear";
    try {
        WorldSettings settings;  // add_car's checks need no mid phase (no plane trees built)
        settings.mid_phase = MidPhaseMode::none;
        World(statics, settings).add_car(spec, placed);
    } catch (const Error& e) {
        return ::testing::AssertionFailure() << e.what();
    }
    return ::testing::AssertionSuccess();
}

// Appends the closed box [lo, hi] (12 triangles, outward normals) to the mesh.
void add_box(TriangleMesh& mesh, const glm::dvec3& lo, const glm::dvec3& hi) {
    const auto base = static_cast<std::uint32_t>(mesh.vertices.size());
    for (const double x : {lo.x, hi.x})
        for (const double y : {lo.y, hi.y})
            for (const double z : {lo.z, hi.z}) mesh.vertices.push_back({x, y, z});
    const std::uint32_t faces[][4] = {{0, 1, 3, 2}, {4, 6, 7, 5}, {0, 4, 5, 1},
                                      {2, 3, 7, 6}, {1, 5, 7, 3}, {0, 2, 6, 4}};
    for (const auto& f : faces) {
        mesh.triangles.push_back({base + f[0], base + f[1], base + f[2]});
        mesh.triangles.push_back({base + f[0], base + f[2], base + f[3]});
    }
}

// A flat road with a kerb 0.15 m high under the car's front left wheel (the default car
// faces +Z here, its front left wheel at x = 0.9, z = 1.45): the car rests on the kerb,
// not on the road under its centre, so it sits higher than on the plain road.
TEST(Spawn, KerbUnderOneWheelLiftsTheCar) {
    const CarSpec spec = CarSpec::default_car();
    TriangleMesh mesh = test::flat_grid(40.0, 20);
    add_box(mesh, {0.3, 0.0, 0.5}, {3.0, 0.15, 3.0});
    const auto kerb = test::static_world_of(mesh);
    const auto road = test::static_world_of(test::flat_grid(40.0, 20));
    RigidBodyState on_kerb, on_road;
    for (const double y : {0.2, 0.5, 3.0, 50.0}) {  // inside the kerb, above it, far above
        ASSERT_TRUE(rests(kerb, spec, {0.0, y, 0.0}, heading(0.0), &on_kerb)) << "from " << y;
        ASSERT_TRUE(rests(road, spec, {0.0, y, 0.0}, heading(0.0), &on_road)) << "from " << y;
        EXPECT_GT(on_kerb.position.y, on_road.position.y + 0.01) << "from " << y;
        EXPECT_NEAR(on_road.position.y, spec.lowest_point_depth() + kClearance, kTolerance);
    }
}

TEST(Spawn, RejectsNothingBelowAWallAndBadInput) {
    const CarSpec spec = CarSpec::default_car();
    const auto ground = test::static_world_of(test::flat_grid(20.0, 4));
    EXPECT_NE(test::error_of([&] {
                  place_car_on_surface(*ground, spec, {100, 3, 0}, heading(0));
              }).find("no surface below the car at (100, 3, 0)"),
              std::string::npos);
    // A pillar 30 m tall through the car: no rise by twice the car's size clears it.
    TriangleMesh pillar = test::flat_grid(20.0, 4);
    add_box(pillar, {-0.5, 0.0, -0.5}, {0.5, 30.0, 0.5});
    const auto inside = test::static_world_of(pillar);
    const std::string message = test::error_of([&] {
        place_car_on_surface(*inside, spec, {0, 3, 0}, heading(0));
    });
    EXPECT_NE(message.find("is inside geometry and stays so raised by"), std::string::npos)
        << message;
    EXPECT_NE(test::error_of([&] {
                  place_car_on_surface(*ground, spec, {0, 3, 0}, heading(0), 0.0);
              }).find("clearance must be in (0, 1] m"),
              std::string::npos);
    // A point 1e30 m up: doubles there are 1.4e14 m apart, and the drop used to land the car
    // at y = -1.4e14.
    EXPECT_NE(test::error_of([&] {
                  place_car_on_surface(*ground, spec, {0, 1e30, 0}, heading(0));
              }).find("more than 1e11 m from y = 0"),
              std::string::npos);
    CarSpec bad = spec;
    bad.ellipsoids[0].semi_axes.y = 0.0;
    EXPECT_NE(test::error_of([&] {
                  place_car_on_surface(*ground, bad, {0, 3, 0}, heading(0));
              }).find("semi_axes.y"),
              std::string::npos);
}

// A point strictly inside a random triangle among `candidates` (indices into the mesh).
glm::dvec3 point_in(const TriangleMesh& mesh, const std::vector<std::uint32_t>& candidates,
                    std::mt19937_64& rng) {
    const auto& t = mesh.triangles[candidates[std::uniform_int_distribution<std::size_t>(
        0, candidates.size() - 1)(rng)]];
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    double u = unit(rng), v = unit(rng);
    if (u + v > 1.0) u = 1.0 - u, v = 1.0 - v;
    const glm::dvec3 a = mesh.vertices[t[0]], b = mesh.vertices[t[1]], c = mesh.vertices[t[2]];
    return a + (b - a) * (0.01 + 0.97 * u) + (c - a) * (0.01 + 0.97 * v);
}

// True when nothing steeper than 45 degrees (a wall, a barrier, a building; not a kerb, a
// bank or a slope) comes within 2.5 m across and 0.3 to 2 m above the point: room for a
// car to stand there at any heading.
bool room_for_a_car(const StaticWorld& statics, const glm::dvec3& ground) {
    std::vector<TriangleRef> refs;
    statics.query_aabb({ground + glm::dvec3(-2.5, 0.3, -2.5), ground + glm::dvec3(2.5, 2.0, 2.5)},
                       refs);
    for (const TriangleRef& ref : refs)
        if (std::abs(statics.collider(ref.collider).triangle(ref.triangle).normal().y) <
            std::sqrt(0.5))
            return false;
    return true;
}

// Random points 0.05 to 10 m above random road triangles with room for a car, random
// headings: each gives a car resting on the surface.
void expect_spawns_rest(const std::shared_ptr<const StaticWorld>& statics, const TriangleMesh& mesh,
                        const std::vector<std::uint32_t>& road, int count, std::uint64_t seed) {
    ASSERT_FALSE(road.empty());
    const CarSpec spec = CarSpec::default_car();
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> log_height(std::log(0.05), std::log(10.0)),
        angle(0.0, 2.0 * std::numbers::pi);
    int tried = 0;
    for (int i = 0; i < count; ++i) {
        glm::dvec3 ground;
        do ground = point_in(mesh, road, rng);
        while (!room_for_a_car(*statics, ground) && ++tried < 20 * count);
        ASSERT_LT(tried, 20 * count) << "too few points with room for a car";
        const glm::dvec3 spawn = ground + glm::dvec3(0.0, std::exp(log_height(rng)), 0.0);
        ASSERT_TRUE(rests(statics, spec, spawn, heading(angle(rng))))
            << "spawn " << i << " at (" << spawn.x << ", " << spawn.y << ", " << spawn.z << ")";
    }
}

TEST(Spawn, AnyPointAboveTheGeneratedRoad) {
    const test::TrackWorld& tw = test::default_track();
    // One chunk's road as the candidates (any chunk is alike), the whole track as statics.
    const std::size_t c = tw.track.chunks.size() / 3;
    const TrackChunk& chunk = tw.track.chunks[c];
    std::vector<std::uint32_t> road(chunk.road_triangle_count);
    for (std::uint32_t i = 0; i < road.size(); ++i) road[i] = i;
    expect_spawns_rest(tw.statics, chunk.mesh, road, 200, 5);
}

class RealTrackSpawn : public ::testing::TestWithParam<std::string> {};

// The surface a car can stand on: triangles facing up within 30 degrees (roads, kerbs,
// verges, terrain), not walls.
TEST_P(RealTrackSpawn, AnyPointAboveTheGround) {
    TRACKPHYS_REAL_TRACK_OR_SKIP(mesh, GetParam());
    std::vector<std::uint32_t> ground;
    for (std::uint32_t i = 0; i < mesh.triangles.size(); ++i) {
        const auto& t = mesh.triangles[i];
        const glm::dvec3 n = glm::cross(mesh.vertices[t[1]] - mesh.vertices[t[0]],
                                        mesh.vertices[t[2]] - mesh.vertices[t[0]]);
        if (glm::length(n) > 0.0 && n.y >= std::cos(std::numbers::pi / 6) * glm::length(n))
            ground.push_back(i);
    }
    expect_spawns_rest(test::static_world_of(mesh), mesh, ground, 200, 6);
}

INSTANTIATE_TEST_SUITE_P(Torcs, RealTrackSpawn, ::testing::ValuesIn(test::kRealTracks),
                         test::real_track_test_name);

}  // namespace
}  // namespace trackphys
