// World::car_contacts: the pairs of cars touching at the end of an update, each with the
// deepest of its ellipsoid pairs' contacts at the last sub-step; the same pairs a snapshot
// keeps as touching, and nothing stale after a restore, a removal or a teleport. That they
// do not depend on threads is tested with the bumping field of world_threads_test.cpp.
#include <cstddef>
#include <cstring>
#include <memory>
#include <span>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "support/same_bits.hpp"
#include "trackphys/geometry/ellipsoid_pair.hpp"
#include "trackphys/world/world.hpp"
#include "world/world_scenes.hpp"

namespace trackphys {
namespace {

using test::moving;

using test::head_on_in_free_space;

std::vector<std::pair<std::uint32_t, std::uint32_t>> touching_pairs(const World& world) {
    std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
    for (const CarTouchSnapshot& t : world.save_state().touching)
        pairs.emplace_back(t.car_a, t.car_b);
    return pairs;
}

std::vector<std::pair<std::uint32_t, std::uint32_t>> contact_pairs(const World& world) {
    std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
    for (const CarPairContact& c : world.car_contacts()) pairs.emplace_back(c.car_a, c.car_b);
    return pairs;
}

using test::same_bits;

// Runs `world` until a pair of cars is touching at the end of an update; returns the
// world's snapshot from before that update.
WorldSnapshot snapshot_before_touching(World& world) {
    WorldSnapshot before = world.save_state();
    for (int u = 0; u < 1000; ++u) {
        world.update();
        if (!world.car_contacts().empty()) return before;
        world.save_state(before);
    }
    ADD_FAILURE() << "the cars never touched";
    return before;
}

TEST(CarContacts, AreThePairsTouchingAtTheEndOfEachUpdate) {
    World world = head_on_in_free_space();
    int updates_touching = 0;
    for (int u = 0; u < 200; ++u) {
        world.update();
        ASSERT_EQ(contact_pairs(world), touching_pairs(world)) << "update " << u;
        for (const CarPairContact& c : world.car_contacts()) {
            EXPECT_LT(c.ellipsoid_a, world.car(c.car_a).ellipsoid_count());
            EXPECT_LT(c.ellipsoid_b, world.car(c.car_b).ellipsoid_count());
            EXPECT_GT(c.contact.depth, 0.0);
            EXPECT_NEAR(glm::length(c.contact.normal), 1.0, 1e-12);
            EXPECT_LT(c.contact.normal.z, -0.5) << "moving car 1 back along -Z separates them";
            EXPECT_GT(c.contact.point.z, world.car(1).state().position.z);
            EXPECT_LT(c.contact.point.z, world.car(2).state().position.z);
        }
        updates_touching += !world.car_contacts().empty();
    }
    EXPECT_GT(updates_touching, 0) << "the cars never touched: the test would prove little";
    EXPECT_TRUE(world.car_contacts().empty()) << "the cars bounced apart";
}

// With one sub-step an update, the cars' ellipsoids at its start are those of its only
// sub-step: the contact reported is the deepest of every ellipsoid pair's, bit for bit, and
// names that pair (the first of equal depths, in the order a's ellipsoids, then b's).
TEST(CarContacts, AreTheDeepestEllipsoidPairOfTheLastSubStep) {
    WorldSettings settings;
    settings.steps = 1;
    settings.substeps = 1;
    settings.dt_update = WorldSettings{}.substep_dt();
    World world = head_on_in_free_space(settings);
    int checked = 0;
    for (int u = 0; u < 8000 && checked < 20; ++u) {
        const Car a = world.car(1);  // copies: the cars as the sub-step places them
        const Car b = world.car(2);
        world.update();
        if (world.car_contacts().empty()) continue;
        ASSERT_EQ(world.car_contacts().size(), 1u);
        CarPairContact deepest;
        for (std::uint32_t i = 0; i < a.ellipsoid_count(); ++i)
            for (std::uint32_t j = 0; j < b.ellipsoid_count(); ++j) {
                const Contact c =
                    ellipsoid_ellipsoid_contact(a.world_ellipsoid(i), b.world_ellipsoid(j));
                if (c.depth > deepest.contact.depth) deepest = {1, 2, i, j, c};
            }
        const CarPairContact& reported = world.car_contacts()[0];
        EXPECT_EQ(reported.car_a, 1u);
        EXPECT_EQ(reported.car_b, 2u);
        EXPECT_EQ(reported.ellipsoid_a, deepest.ellipsoid_a) << "update " << u;
        EXPECT_EQ(reported.ellipsoid_b, deepest.ellipsoid_b) << "update " << u;
        EXPECT_TRUE(same_bits(reported.contact, deepest.contact))
            << "update " << u << ": depth " << reported.contact.depth << ", the deepest pair's "
            << deepest.contact.depth;
        ++checked;
    }
    EXPECT_GT(checked, 5) << "too few updates ended touching to prove much";
}

// The update after a restore gives the contacts the saved world's gave, bit for bit.
bool same_contacts(std::span<const CarPairContact> a, std::span<const CarPairContact> b) {
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i)
        if (a[i].car_a != b[i].car_a || a[i].car_b != b[i].car_b ||
            a[i].ellipsoid_a != b[i].ellipsoid_a || a[i].ellipsoid_b != b[i].ellipsoid_b ||
            !same_bits(a[i].contact, b[i].contact))
            return false;
    return true;
}

// An update of two steps of one sub-step runs the very states of two updates of one
// sub-step each (the same bits): its contacts must be those of the second, its last
// sub-step's, not the first's.
TEST(CarContacts, AreTheUpdatesLastSubSteps) {
    const double h = WorldSettings{}.substep_dt();
    WorldSettings two_steps;
    two_steps.steps = 2;
    two_steps.substeps = 1;
    two_steps.dt_update = 2.0 * h;
    WorldSettings one_step = two_steps;
    one_step.steps = 1;
    one_step.dt_update = h;
    World world = head_on_in_free_space(two_steps);
    World halves = head_on_in_free_space(one_step);
    int touching = 0, first_differs = 0;
    for (int u = 0; u < 4000; ++u) {
        world.update();
        halves.update();
        const std::vector<CarPairContact> first(halves.car_contacts().begin(),
                                                halves.car_contacts().end());
        halves.update();
        for (std::size_t k = 0; k < world.car_count(); ++k)
            ASSERT_EQ(
                std::memcmp(&world.car(k).state(), &halves.car(k).state(), sizeof(RigidBodyState)),
                0)
                << "car " << k << " at update " << u;
        EXPECT_TRUE(same_contacts(world.car_contacts(), halves.car_contacts())) << "update " << u;
        touching += !world.car_contacts().empty();
        first_differs += !same_contacts(first, halves.car_contacts());
    }
    EXPECT_GT(touching, 0) << "the cars never touched: the test would prove little";
    EXPECT_GT(first_differs, 0) << "the first sub-step's contacts were the last's throughout";
}

TEST(CarContacts, ARestoredWorldListsNoneUntilItsNextUpdate) {
    World world = test::one_car_pushing_a_braked_one();
    const WorldSnapshot before_touching = snapshot_before_touching(world);
    const std::vector<CarPairContact> original(world.car_contacts().begin(),
                                               world.car_contacts().end());
    world.restore_state(before_touching);
    EXPECT_TRUE(world.car_contacts().empty()) << "restore_state keeps the last update's contacts";
    world.update();
    ASSERT_EQ(world.car_contacts().size(), original.size());
    for (std::size_t i = 0; i < original.size(); ++i) {
        const CarPairContact& again = world.car_contacts()[i];
        EXPECT_EQ(again.car_a, original[i].car_a);
        EXPECT_EQ(again.car_b, original[i].car_b);
        EXPECT_EQ(again.ellipsoid_a, original[i].ellipsoid_a);
        EXPECT_EQ(again.ellipsoid_b, original[i].ellipsoid_b);
        EXPECT_TRUE(same_bits(again.contact, original[i].contact));
    }
}

TEST(CarContacts, ARemovedCarsPairsAreDropped) {
    World world = test::one_car_pushing_a_braked_one();
    snapshot_before_touching(world);
    world.remove_car(0);
    EXPECT_TRUE(world.car_contacts().empty()) << "remove_car keeps contacts of stale indices";
}

TEST(CarContacts, ATeleportedCarsPairsAreDropped) {
    World world = test::one_car_pushing_a_braked_one();
    snapshot_before_touching(world);
    // At rest on the ground, 50 m to the side.
    world.teleport_car(1, moving({50.0, CarSpec::default_car().lowest_point_depth() + 0.001, 0.0},
                                 glm::dvec3(0.0)));
    EXPECT_TRUE(world.car_contacts().empty()) << "the moved car's pair is still listed";
    world.update();
    EXPECT_TRUE(world.car_contacts().empty()) << "the cars are 50 m apart";
}

}  // namespace
}  // namespace trackphys
