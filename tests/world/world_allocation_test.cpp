// World::update allocates nothing once a field of cars has warmed up (issue 16): every
// buffer an update needs is kept between updates. A binary of its own, because it replaces
// the global operator new to count the allocations made inside World::update, on every
// thread of the world's pool.
#include <atomic>
#include <cstdint>
#include <cstdlib>
#include <new>

#include <gtest/gtest.h>

#include "trackphys/world/race_drivers.hpp"
#include "trackphys/world/world.hpp"
#include "world/track_world.hpp"

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
    for (int u = 0; u < kWarmUpdates + kCountedUpdates; ++u) {
        drivers.drive(world);
        counting.store(u >= kWarmUpdates);
        world.update();
        counting.store(false);
        drivers.after_update(world);
        if (u >= kWarmUpdates) contacts += world.last_profile().car_contacts;
    }
    EXPECT_EQ(allocations.load(), 0u) << "allocations in " << kCountedUpdates << " updates";
    EXPECT_GT(contacts, 0u) << "the counted updates had no car-car contact to allocate for";
}

INSTANTIATE_TEST_SUITE_P(FrameSources, WorldAllocation,
                         ::testing::Values(PlaneTreeFrames::kept, PlaneTreeFrames::built),
                         [](const ::testing::TestParamInfo<PlaneTreeFrames>& source) {
                             return source.param == PlaneTreeFrames::kept ? "kept" : "built";
                         });

}  // namespace
}  // namespace trackphys
