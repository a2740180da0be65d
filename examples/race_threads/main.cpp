// A field of cars on many threads: World spreads islands of cars (cars whose update boxes
// meet) over its own threads or over the game's job system, and the result is the same bits
// either way. Eight cars start on a ring facing its centre and crash into each other there.
#include <algorithm>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>
#include <thread>
#include <vector>

#include <glm/gtc/quaternion.hpp>
#include <trackphys/world/spawn.hpp>
#include <trackphys/world/world.hpp>

using namespace trackphys;

// A game's job system, cut to the bone: World hands it the update's islands as items, it
// cuts them into at most kWorkers ranges, runs each on a thread of its own under a distinct
// worker index, and finish_task waits for them.
constexpr int kWorkers = 4;
struct GameJobs {
    std::vector<std::thread> running;
};
void* enqueue_task(TaskCallback* task, int items, int min_range, void* world, void* jobs) {
    auto& game = *static_cast<GameJobs*>(jobs);
    const int per_range = std::max(min_range, (items + kWorkers - 1) / kWorkers);
    for (int begin = 0, worker = 0; begin < items; begin += per_range, ++worker)
        game.running.emplace_back(task, begin, std::min(items, begin + per_range), worker, world);
    return &game;
}
void finish_task(void* task, void* /*jobs*/) {
    auto& game = *static_cast<GameJobs*>(task);
    for (std::thread& t : game.running) t.join();
    game.running.clear();
}

struct Outcome {
    std::uint64_t hash;
    std::size_t touches;
};

Outcome race(WorldSettings settings) {
    TriangleMesh ground;  // 200 m x 200 m at y = 0
    ground.vertices = {{-100, 0, -100}, {100, 0, -100}, {100, 0, 100}, {-100, 0, 100}};
    ground.triangles = {{0, 3, 2}, {0, 2, 1}};
    auto statics = std::make_shared<StaticWorld>();
    statics->add(std::make_shared<StaticCollider>(ground));
    World world(statics, settings);

    const CarSpec spec = CarSpec::default_car();
    for (int i = 0; i < 8; ++i) {
        const double a = 2.0 * std::numbers::pi * i / 8.0;
        const glm::dvec3 at(15.0 * std::cos(a), 1.0, 15.0 * std::sin(a));
        // The car's forward is +Z: turned about +Y to face the ring's centre.
        const double heading = std::atan2(-at.x, -at.z);
        const glm::dquat facing = glm::angleAxis(heading, glm::dvec3(0.0, 1.0, 0.0));
        world.add_car(spec, place_car_on_surface(*statics, spec, at, facing));
        world.car(i).set_inputs({.throttle = 0.6 + 0.05 * i, .brake = 0.0, .steer = 0.0});
    }
    std::size_t touches = 0;
    for (int update = 0; update < 300; ++update) {  // three seconds
        world.update();
        touches += world.contact_events().car_touch_begins.size();
    }
    return {world.state_hash(), touches};
}

int main() {
    WorldSettings one_thread;  // the default: World updates on the calling thread
    WorldSettings two_threads;
    two_threads.threads = 2;  // World's own pool
    GameJobs game;
    WorldSettings jobs;
    jobs.jobs = {.enqueue_task = enqueue_task,
                 .finish_task = finish_task,
                 .user_context = &game,
                 .worker_count = kWorkers};

    const Outcome a = race(one_thread), b = race(two_threads), c = race(jobs);
    const bool alike =
        a.hash == b.hash && b.hash == c.hash && a.touches == b.touches && b.touches == c.touches;
    std::printf("8 cars, 3 s, %zu car touches: state hash %016" PRIx64
                " on 1 thread, 2 threads and the game's jobs %s\n",
                a.touches, a.hash, alike ? "alike" : "DIFFER");
    return alike && a.touches > 0 ? 0 : 1;
}
