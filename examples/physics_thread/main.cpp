// The physics on a thread of its own, as a game runs it beside its renderer: PhysicsRunner
// owns the World, the game thread stamps inputs for the update they apply at, and the render
// thread reads each car's pose between the last two published states, without locks.
#include <atomic>
#include <chrono>
#include <cstdio>
#include <memory>
#include <thread>

#include <trackphys/world/physics_runner.hpp>

using namespace trackphys;

int main() {
    TriangleMesh ground;  // 200 m x 200 m at y = 0
    ground.vertices = {{-100, 0, -100}, {100, 0, -100}, {100, 0, 100}, {-100, 0, 100}};
    ground.triangles = {{0, 3, 2}, {0, 2, 1}};
    auto statics = std::make_shared<StaticWorld>();
    statics->add(std::make_shared<StaticCollider>(ground));
    World world(statics);
    RigidBodyState start;
    start.position = {0.0, 0.6, 0.0};
    world.add_car(CarSpec::default_car(), start);

    // In real time: one update per 10 ms of wall clock, one second in all.
    PhysicsRunner runner(std::move(world));
    runner.set_inputs(1, 0, {.throttle = 1.0, .brake = 0.0, .steer = 0.0});
    runner.set_inputs(50, 0, {.throttle = 0.0, .brake = 1.0, .steer = 0.0});  // at 0.5 s

    // The render thread draws a frame every 1/60 s at a simulated time from its own clock,
    // one update behind the wall clock, so that the states around it are (nearly always)
    // published; it only checks that each pose it reads stands on the ground. (A time
    // taken from published_update() and a pose read after it may come from two frames.)
    std::atomic<bool> done = false;
    int frames = 0, off_ground = 0;
    const auto started = std::chrono::steady_clock::now();
    std::thread render([&] {
        while (!done.load()) {
            const std::chrono::duration<double> wall = std::chrono::steady_clock::now() - started;
            const double t = wall.count() - 0.01;
            const CarPose pose = runner.pose(0, t);
            off_ground += !(pose.position.y > 0.0 && pose.position.y < 1.0);
            ++frames;
            std::this_thread::sleep_for(std::chrono::microseconds(16'667));
        }
    });
    runner.run_to(100);
    runner.wait();  // the game thread would run its own frames meanwhile
    done = true;
    render.join();

    const World& after = runner.world();
    const double speed = after.car(0).speed();
    std::printf(
        "update %llu: %d frames drawn (%d off the ground), car at z = %.1f m, "
        "%.2f m/s after braking\n",
        static_cast<unsigned long long>(after.update_count()), frames, off_ground,
        after.car(0).state().position.z, speed);
    return after.update_count() == 100 && frames > 0 && off_ground == 0 && speed < 1.0 ? 0 : 1;
}
