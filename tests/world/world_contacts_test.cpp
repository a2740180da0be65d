// World's road contacts against brute force: whatever the cull, the order of the survivors
// and the bounds that skip exact tests (World::find_contacts), each ellipsoid's contact is
// the deepest over every triangle near it, and where it touches nothing it is no contact.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include <glm/vec3.hpp>

#include "trackphys/geometry/contact.hpp"
#include "trackphys/world/race_drivers.hpp"
#include "trackphys/world/world.hpp"
#include "world/track_world.hpp"

namespace trackphys {
namespace {

// The deepest contact of the ellipsoid over every triangle whose box meets its box: a
// triangle outside it cannot touch the ellipsoid.
double brute_force_depth(const StaticWorld& statics, const Ellipsoid& ellipsoid) {
    std::vector<TriangleRef> near;
    statics.query_aabb(ellipsoid.bounds(), near);
    double deepest = -std::numeric_limits<double>::infinity();
    for (const TriangleRef& ref : near) {
        const Triangle triangle = statics.collider(ref.collider).triangle(ref.triangle);
        deepest = std::max(deepest, ellipsoid_triangle_contact(ellipsoid, triangle).depth);
    }
    return deepest;
}

// One sub-step per update, so that World::contacts are those of the state the update
// started from; 4 s of the autopilot from the grid, over the first bends.
TEST(WorldContacts, AreTheDeepestOverEveryTriangleNearby) {
    const test::TrackWorld& tw = test::default_track();
    WorldSettings settings;
    settings.threads = 1;
    settings.steps = 1;
    settings.substeps = 1;
    settings.dt_update = 0.01 / 40.0;  // the default sub-step
    World world(tw.statics, settings, tw.trees);
    RaceDrivers drivers(tw.track, CarSpec::default_car(), 1);
    drivers.add_cars(world);

    std::size_t touching = 0, apart = 0;
    for (int update = 0; update < 16000; ++update) {
        drivers.drive(world);
        const Car before = world.car(0);
        world.update();
        drivers.after_update(world);
        const std::span<const Contact> found = world.contacts(0);
        for (std::size_t i = 0; i < before.ellipsoid_count(); ++i) {
            const double expected = brute_force_depth(*tw.statics, before.world_ellipsoid(i));
            if (!(expected > 0.0) && !(found[i].depth > 0.0)) {
                // As World::contacts documents it, whatever the exact tests met on the way.
                apart += std::isfinite(expected);
                ASSERT_EQ(found[i].depth, -std::numeric_limits<double>::infinity())
                    << "update " << update << ", ellipsoid " << i;
                ASSERT_EQ(found[i].normal, glm::dvec3(0.0)) << "update " << update;
                ASSERT_EQ(found[i].point, glm::dvec3(0.0)) << "update " << update;
                continue;
            }
            ++touching;
            ASSERT_NEAR(found[i].depth, expected, 1e-9)
                << "update " << update << ", ellipsoid " << i;
        }
    }
    EXPECT_GT(touching, 16000u * 3) << "the wheels left the road";
    EXPECT_GT(apart, 0u) << "no ellipsoid came near the road without touching it";
    EXPECT_EQ(world.car_resets(0), 0u);
}

}  // namespace
}  // namespace trackphys
