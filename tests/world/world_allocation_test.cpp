// World::update allocates nothing once a field of cars has warmed up (issue 16): every
// buffer an update needs is kept between updates, its contact events' too; nor does
// PhysicsRunner's publishing of each update, nor a render thread's reading of it, nor saving
// into a kept snapshot and restoring one, which rollback netcode does every frame, nor a
// recording's frame. A binary of its own, because it replaces the global operator new to
// count the allocations made inside World::update, on every thread of the world's pool, and
// on the runner's physics thread.
#include <atomic>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <new>
#include <string>

#include <gtest/gtest.h>
#include <unistd.h>

#include "tool_world_settings.hpp"
#include "trackphys/io/recording.hpp"
#include "trackphys/world/physics_runner.hpp"
#include "trackphys/world/race_drivers.hpp"
#include "trackphys/world/world.hpp"
#include "world/track_world.hpp"
#include "world/world_scenes.hpp"

namespace {

std::atomic<bool> counting{false};
std::atomic<std::uint64_t> allocations{0};

void* allocate(std::size_t bytes, std::size_t alignment) {
    if (counting.load(std::memory_order_relaxed))
        allocations.fetch_add(1, std::memory_order_relaxed);
    const std::size_t size = bytes == 0 ? 1 : bytes;
    void* p = alignment <= alignof(std::max_align_t)
                  ? std::malloc(size)
                  : std::aligned_alloc(alignment, (size + alignment - 1) / alignment * alignment);
    if (!p) throw std::bad_alloc();
    return p;
}

}  // namespace

void* operator new(std::size_t bytes) { return allocate(bytes, alignof(std::max_align_t)); }
void* operator new(std::size_t bytes, std::align_val_t alignment) {
    return allocate(bytes, static_cast<std::size_t>(alignment));
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }

namespace trackphys {
namespace {

// How many allocations `work` makes.
template <typename Work>
std::uint64_t allocations_in(Work&& work) {
    allocations.store(0);
    counting.store(true);
    work();
    counting.store(false);
    return allocations.load();
}

// Run with the plane trees' frames kept (the default track's, within the budget) and built
// into each car's frame cache (a budget of 0, as on a map too big to keep them).
class WorldAllocation : public ::testing::TestWithParam<PlaneTreeFrames> {};

TEST_P(WorldAllocation, ARaceOnTwoThreadsAllocatesNothingOnceWarm) {
    constexpr std::size_t kCars = 12;
    constexpr int kWarmUpdates = 2000;     // 20 s: the start, the field strung out
    constexpr int kCountedUpdates = 2000;  // 20 s more, with car-car contacts
    const test::TrackWorld& track = test::default_track();
    const std::size_t budget = GetParam() == PlaneTreeFrames::kept ? kPlaneTreeFrameBudget : 0;
    const ColliderPlaneTrees trees =
        make_collider_plane_trees(*track.statics, PlaneTreeSettings::precomputed(), 0, budget);
    ASSERT_EQ(trees.front()->keeps_frames(), GetParam() == PlaneTreeFrames::kept);
    WorldSettings settings;
    settings.threads = 2;
    World world(track.statics, settings, trees);
    RaceDrivers drivers(track.track, CarSpec::default_car(), kCars);
    drivers.add_cars(world);

    std::uint64_t contacts = 0;
    std::uint64_t touches = 0;
    for (int u = 0; u < kWarmUpdates + kCountedUpdates; ++u) {
        drivers.drive(world);
        counting.store(u >= kWarmUpdates);
        world.update();
        counting.store(false);
        drivers.after_update(world);
        if (u >= kWarmUpdates) {
            contacts += world.last_profile().car_contacts;
            touches += world.contact_events().car_touch_begins.size();
        }
    }
    EXPECT_EQ(allocations.load(), 0u) << "allocations in " << kCountedUpdates << " updates";
    EXPECT_GT(contacts, 0u) << "the counted updates had no car-car contact to allocate for";
    EXPECT_GT(touches, 0u) << "the counted updates began no touch to record";
}

INSTANTIATE_TEST_SUITE_P(FrameSources, WorldAllocation,
                         ::testing::Values(PlaneTreeFrames::kept, PlaneTreeFrames::built),
                         [](const ::testing::TestParamInfo<PlaneTreeFrames>& source) {
                             return source.param == PlaneTreeFrames::kept ? "kept" : "built";
                         });

// Two vehicle-model cars driving on flat ground on a runner: once warm, a run of 200 updates
// allocates what a run of none does (the physics thread's start), so publishing the views
// allocates nothing; a render thread reading a view into a CarView it keeps allocates
// nothing either.
TEST(PhysicsRunnerAllocation, PublishingAndReadingViewsAllocateNothingOnceWarm) {
    World world(test::static_world_of(test::flat_grid(400.0, 40)), cli::tool_world_settings());
    const CarSpec spec = CarSpec::preset("gt");
    for (const double x : {-3.0, 3.0}) {
        RigidBodyState state;
        state.position = {x, spec.lowest_point_depth() + 0.001, -150.0};
        world.add_car(spec, state);
    }
    PhysicsRunner runner(std::move(world), false);
    runner.set_inputs(1, 0, {1.0, 0.0, 0.3});
    runner.set_inputs(1, 1, {0.8, 0.0, -0.3});
    runner.run_to(200);
    runner.wait();
    const auto allocations_of_run_to = [&](std::uint64_t last_update) {
        return allocations_in([&] {
            runner.run_to(last_update);
            runner.wait();
        });
    };
    const std::uint64_t start_only = allocations_of_run_to(200);
    EXPECT_EQ(allocations_of_run_to(400), start_only) << "allocations in 200 updates";

    const double t = runner.world().time() - 0.005;
    CarView view;
    runner.view(0, t, view);
    EXPECT_EQ(allocations_in([&] {
                  runner.view(1, t, view);
                  runner.view(0, t + 1.0, view);
              }),
              0u);
    EXPECT_EQ(view.wheels.size(), 4u);
}

// Eight gt cars driving on flat ground: once a snapshot has been saved into, saving into it
// again and restoring it allocate nothing, and the restore gives the saved world's bits.
TEST(WorldSnapshotAllocation, SavingIntoAKeptSnapshotAndRestoringAllocateNothing) {
    World world(test::static_world_of(test::flat_grid(400.0, 40)));
    const CarSpec spec = CarSpec::preset("gt");
    for (int k = 0; k < 8; ++k) {
        RigidBodyState state;
        state.position = {-14.0 + 4.0 * k, spec.lowest_point_depth() + 0.001, -150.0};
        world.add_car(spec, state);
        world.car(static_cast<std::size_t>(k)).set_inputs({1.0, 0.0, 0.05 * (k - 4)});
    }
    for (int u = 0; u < 50; ++u) world.update();
    WorldSnapshot kept;
    world.save_state(kept);  // the first save grows the vectors
    for (int u = 0; u < 50; ++u) world.update();

    EXPECT_EQ(allocations_in([&] { world.save_state(kept); }), 0u) << "saving into a kept snapshot";
    const std::uint64_t saved_hash = world.state_hash();
    ASSERT_EQ(kept.cars.size(), 8u);
    ASSERT_TRUE(kept.cars[0].vehicle.has_value());

    for (int u = 0; u < 50; ++u) world.update();
    ASSERT_NE(world.state_hash(), saved_hash);
    EXPECT_EQ(allocations_in([&] { world.restore_state(kept); }), 0u) << "restoring";
    EXPECT_EQ(world.state_hash(), saved_hash);
}

// A recording's frames allocate nothing once the writer has written one of as many cars,
// also the first frame that lists cars touching (its contacts were once gathered into a list
// that grew then).
TEST(RecordingAllocation, FramesOfCarsInContactAllocateNothing) {
    World world = test::one_car_pushing_a_braked_one();
    RecordingHeader header;
    header.car_ellipsoids.assign(2, CarSpec::default_car().ellipsoids);
    const std::filesystem::path file =
        std::filesystem::temp_directory_path() /
        ("trackphys_recording_allocation_" + std::to_string(::getpid()) + ".jsonl");
    RecordingWriter writer(file, header);
    world.update();
    writer.write_frame(world);  // warms the writer's per-car lists
    int touching = 0;
    for (int u = 0; u < 300; ++u) {
        world.update();
        touching += !world.car_contacts().empty();
        EXPECT_EQ(allocations_in([&] { writer.write_frame(world); }), 0u) << "update " << u;
    }
    EXPECT_GT(touching, 0) << "the cars never touched: the test would prove little";
    writer.finish();
    std::filesystem::remove(file);
}

// A rollback restores most often while cars are in contact: a gt pushing a braked one, so
// the snapshot holds touching pairs, whose check used to build a string each.
TEST(WorldSnapshotAllocation, RestoringCarsInContactAllocatesNothing) {
    World world(test::static_world_of(test::flat_grid(400.0, 40)));
    const CarSpec spec = CarSpec::preset("gt");
    for (const double z : {-150.0, -156.0}) {
        RigidBodyState state;
        state.position = {0.0, spec.lowest_point_depth() + 0.001, z};
        world.add_car(spec, state);
    }
    world.car(0).set_inputs({0.0, 1.0, 0.0});
    world.car(1).set_inputs({1.0, 0.0, 0.0});
    for (int u = 0; u < 300; ++u) world.update();
    WorldSnapshot kept;
    world.save_state(kept);
    ASSERT_FALSE(kept.touching.empty()) << "the cars are not in contact";
    const std::uint64_t saved_hash = world.state_hash();
    for (int u = 0; u < 20; ++u) world.update();
    world.restore_state(kept);  // warms the touching lists

    EXPECT_EQ(allocations_in([&] { world.restore_state(kept); }), 0u) << "restoring";
    EXPECT_EQ(world.state_hash(), saved_hash);
}

}  // namespace
}  // namespace trackphys
