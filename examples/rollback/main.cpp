// Rollback netcode's loop: save the world every frame into one kept snapshot (no allocation
// once warm), and when a remote player's late input arrives, restore the frame it belongs to
// and simulate forward again. The same inputs from the same snapshot give the same bits and
// the same contact events as a world that knew them all along.
#include <cinttypes>
#include <cstdio>
#include <memory>
#include <vector>

#include <trackphys/world/world.hpp>

using namespace trackphys;

// Two cars side by side; car 1 is the remote player's and swerves into car 0 from update 30
// on, which the local simulation learns only at update 60 (until then it predicts the last
// input it knew: straight on).
constexpr std::uint64_t kSwerve = 30, kArrival = 60, kEnd = 200;

struct Race {
    World world;
    std::vector<std::size_t> touches;  // car touches begun, per update

    void step(bool remote_known) {
        const std::uint64_t next = world.update_count() + 1;
        const bool swerving = remote_known && next >= kSwerve;
        world.car(0).set_inputs({.throttle = 0.8, .brake = 0.0, .steer = 0.0});
        world.car(1).set_inputs({.throttle = 0.8, .brake = 0.0, .steer = swerving ? -0.6 : 0.0});
        world.update();
        touches.resize(world.update_count() + 1);
        touches[world.update_count()] = world.contact_events().car_touch_begins.size();
    }
};

Race make_race() {
    TriangleMesh ground;  // 200 m x 200 m at y = 0
    ground.vertices = {{-100, 0, -100}, {100, 0, -100}, {100, 0, 100}, {-100, 0, 100}};
    ground.triangles = {{0, 3, 2}, {0, 2, 1}};
    auto statics = std::make_shared<StaticWorld>();
    statics->add(std::make_shared<StaticCollider>(ground));
    Race race{World(statics), {}};
    RigidBodyState left, right;  // the cars face +Z; +X is their left
    left.position = {2.5, 0.6, 0.0};
    right.position = {-2.5, 0.6, 0.0};
    race.world.add_car(CarSpec::default_car(), right);  // car 0, this player's
    race.world.add_car(CarSpec::default_car(), left);   // car 1, swerving right into it
    return race;
}

int main() {
    Race truth = make_race();  // what every player sees once all inputs are in
    while (truth.world.update_count() < kEnd) truth.step(true);

    Race local = make_race();
    WorldSnapshot saved;  // kept and reused: a game keeps one per frame of its window
    while (local.world.update_count() < kArrival) {
        if (local.world.update_count() == kSwerve - 1) local.world.save_state(saved);
        local.step(false);
    }
    local.world.restore_state(saved);  // back to the frame before the swerve
    while (local.world.update_count() < kEnd) local.step(true);

    std::size_t touches = 0;
    for (const std::size_t n : truth.touches) touches += n;
    const bool same =
        local.world.state_hash() == truth.world.state_hash() && local.touches == truth.touches;
    std::printf("rolled back %llu updates: %zu car touches, state hash %016" PRIx64 " %s\n",
                static_cast<unsigned long long>(kArrival - kSwerve + 1), touches,
                local.world.state_hash(), same ? "as if never predicted" : "DIFFERS");
    return same && touches > 0 ? 0 : 1;
}
