// A field of cars that touch, on 1, 2 and 4 threads and on a plugged-in job system: the
// same bits, the same contact events and car contacts every time (World's class notes), across
// save_state / restore_state and with cars removed on the way.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/fnv1a.hpp"
#include "support/error_message.hpp"
#include "trackphys/error.hpp"
#include "trackphys/world/autopilot.hpp"
#include "trackphys/world/race_grid.hpp"
#include "trackphys/world/world.hpp"
#include "world/track_world.hpp"

namespace trackphys {
namespace {

constexpr std::size_t kCars = 10;

// The grid of the default track, every car on an autopilot of its own speed (faster ones
// further back), all aiming at the centreline: they bump as they merge.
class Field {
  public:
    explicit Field(WorldSettings settings)
        : world_(test::default_track().statics, settings, test::default_track().trees) {
        const test::TrackWorld& track = test::default_track();
        const CarSpec spec = CarSpec::default_car();
        for (const RigidBodyState& start : race_grid(track.track, *track.statics, spec, kCars)) {
            AutopilotSettings driver;
            driver.target_speed = (250.0 + 15.0 * static_cast<double>(pilots_.size())) / 3.6;
            pilots_.emplace_back(track.track, spec, driver);
            world_.add_car(spec, start);
        }
    }

    // Runs `updates` updates; returns the car-car contacts seen.
    std::uint64_t run(int updates) {
        std::uint64_t contacts = 0;
        for (int u = 0; u < updates; ++u) {
            for (std::size_t i = 0; i < world_.car_count(); ++i)
                world_.car(i).set_inputs(pilots_[i].drive(world_.car(i)));
            world_.update();
            contacts += world_.last_profile().car_contacts;
            add_events();
        }
        return contacts;
    }

    // Every contact event so far, in order, bit for bit.
    std::uint64_t events_hash() const { return events_.value; }
    std::uint64_t touches_begun() const { return touches_begun_; }
    // The events from here on only.
    void restart_events() { events_ = {}; }

    // Car i retires: its autopilot goes with it.
    void remove(std::size_t i) {
        world_.remove_car(i);
        pilots_.erase(pilots_.begin() + static_cast<std::ptrdiff_t>(i));
    }

    World& world() { return world_; }
    std::vector<Autopilot>& pilots() { return pilots_; }

  private:
    void add_events() {
        const ContactEvents events = world_.contact_events();
        touches_begun_ += events.car_touch_begins.size();
        for (const CarTouchBeginEvent& e : events.car_touch_begins) {
            events_.add(std::uint64_t{e.car_a} << 32 | e.car_b);
            events_.add(e.point), events_.add(e.normal);
            events_.add(e.depth), events_.add(e.approach_speed);
        }
        for (const CarTouchEndEvent& e : events.car_touch_ends) {
            events_.add(std::uint64_t{e.car_a} << 32 | e.car_b);
            events_.add(e.deepest);
        }
        for (const BodyHitEvent& e : events.body_hits) {
            events_.add(std::uint64_t{e.car} << 32 | e.ellipsoid);
            events_.add(std::uint64_t{e.triangle.collider} << 32 | e.triangle.triangle);
            events_.add(e.point), events_.add(e.normal);
            events_.add(e.depth), events_.add(e.approach_speed);
        }
        for (const CarPairContact& c : world_.car_contacts()) {
            events_.add(std::uint64_t{c.car_a} << 32 | c.car_b);
            events_.add(std::uint64_t{c.ellipsoid_a} << 32 | c.ellipsoid_b);
            events_.add(c.contact.point), events_.add(c.contact.normal);
            events_.add(c.contact.depth);
        }
        // Where one update's events end: the same events split otherwise hash otherwise.
        events_.add(std::uint64_t{0});
    }

    World world_;
    std::vector<Autopilot> pilots_;
    core::Fnv1a events_;
    std::uint64_t touches_begun_ = 0;
};

WorldSettings on_threads(int threads) {
    WorldSettings settings;
    settings.threads = threads;
    return settings;
}

constexpr int kFieldUpdates = 300;

TEST(WorldThreads, SameHashOnOneTwoAndFourThreads) {
    Field reference(on_threads(1));
    const std::uint64_t contacts = reference.run(kFieldUpdates);
    EXPECT_GT(contacts, 0u) << "the field never touched: the test would prove little";
    EXPECT_GT(reference.touches_begun(), 0u) << "no touch began: the events went unrecorded";
    const std::uint64_t expected = reference.world().state_hash();
    for (const int threads : {1, 2, 4, 2, 4}) {
        Field field(on_threads(threads));
        field.run(kFieldUpdates);
        EXPECT_EQ(field.world().state_hash(), expected) << threads << " threads";
        EXPECT_EQ(field.events_hash(), reference.events_hash()) << threads << " threads";
    }
}

// Cars retire from the bumping field (one from the middle, then the first and the last),
// each after the same update: the same bits on every thread count.
TEST(WorldThreads, SameRemovalsGiveTheSameHashOnAnyThreadCount) {
    const auto run_with_removals = [](int threads) {
        Field field(on_threads(threads));
        std::uint64_t contacts = field.run(100);
        field.remove(4);
        contacts += field.run(100);
        field.remove(0);
        field.remove(field.world().car_count() - 1);
        contacts += field.run(100);
        EXPECT_EQ(field.world().car_count(), kCars - 3);
        EXPECT_GT(contacts, 0u) << "the field never touched: the test would prove little";
        return field.world().state_hash();
    };
    const std::uint64_t expected = run_with_removals(1);
    for (const int threads : {2, 4}) EXPECT_EQ(run_with_removals(threads), expected) << threads;
}

// A job system that runs the ranges backwards, one item at a time, each on another worker
// index: order and worker must not matter.
struct BackwardsJobs {
    int enqueued = 0;
    static void* enqueue(TaskCallback* task, int items, int min_range, void* context, void* user) {
        auto& self = *static_cast<BackwardsJobs*>(user);
        EXPECT_GE(min_range, 1);
        ++self.enqueued;
        for (int item = items - 1; item >= 0; --item) task(item, item + 1, item % 3, context);
        return &self;
    }
    static void finish(void* task, void* user) { EXPECT_EQ(task, user); }
};

TEST(WorldThreads, PluggedInJobSystemGivesTheSameHash) {
    Field reference(on_threads(1));
    reference.run(kFieldUpdates);

    BackwardsJobs jobs;
    WorldSettings settings;
    settings.jobs = {&BackwardsJobs::enqueue, &BackwardsJobs::finish, &jobs, 3};
    Field field(settings);
    field.run(kFieldUpdates);
    EXPECT_EQ(field.world().state_hash(), reference.world().state_hash());
    EXPECT_EQ(field.events_hash(), reference.events_hash());
    EXPECT_EQ(jobs.enqueued, kFieldUpdates);
}

// BackwardsJobs runs items on workers 0, 1 and 2: a job system that says it has two
// workers must not hand World a third's index to write scratch memory that is not there.
TEST(WorldThreads, AWorkerIndexPastWorkerCountIsAnError) {
    BackwardsJobs jobs;
    WorldSettings settings;
    settings.jobs = {&BackwardsJobs::enqueue, &BackwardsJobs::finish, &jobs, 2};
    Field field(settings);
    const std::string why = test::error_of([&] { field.run(1); });
    EXPECT_NE(why.find("worker 2, outside 0 .. worker_count - 1 = 1"), std::string::npos) << why;
}

// Saved at the first update from the 150th on that ends with cars touching: the resumed
// field gives the same bits and the same events (no touch begins twice).
TEST(WorldThreads, SnapshotOfTheWholeFieldResumesBitForBit) {
    Field through(on_threads(2));
    through.run(150);
    WorldSnapshot snapshot = through.world().save_state();
    for (int u = 0; u < 300 && snapshot.touching.empty(); ++u) {
        through.run(1);
        through.world().save_state(snapshot);
    }
    std::vector<AutopilotProgress> progress;
    for (const Autopilot& pilot : through.pilots()) progress.push_back(pilot.progress());
    EXPECT_EQ(snapshot.cars.size(), kCars);
    EXPECT_FALSE(snapshot.touching.empty()) << "no car touching: the events would prove little";
    through.restart_events();
    through.run(150);

    Field resumed(on_threads(1));
    resumed.world().restore_state(snapshot);
    for (std::size_t i = 0; i < kCars; ++i) resumed.pilots()[i].set_progress(progress[i]);
    resumed.run(150);
    EXPECT_EQ(resumed.world().state_hash(), through.world().state_hash());
    EXPECT_EQ(resumed.events_hash(), through.events_hash());
}

TEST(WorldThreads, SettingsRejectBadThreadsAndHalfAJobSystem) {
    WorldSettings settings;
    settings.threads = -1;
    EXPECT_NE(settings.validate().find("WorldSettings.threads"), std::string::npos);
    settings.threads = 2;
    settings.jobs.enqueue_task = &BackwardsJobs::enqueue;
    EXPECT_NE(settings.validate().find("WorldSettings.jobs"), std::string::npos);
    settings.jobs.finish_task = &BackwardsJobs::finish;
    settings.jobs.worker_count = 0;
    EXPECT_NE(settings.validate().find("worker_count"), std::string::npos);
    settings.jobs.worker_count = 1;
    EXPECT_EQ(settings.validate(), "");
}

}  // namespace
}  // namespace trackphys
