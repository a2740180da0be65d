// What World::debug_draw costs, and that update() pays nothing for it: three identical
// drives of the default car on the default track (seed 7, autopilot), one never drawn, one
// drawn after every update with the default options (cars, ellipsoids, contacts) and one
// with every option (also update boxes, listed and kept triangles). They take turns by
// blocks of 10 updates, so a busy moment of the shared machine falls on all of them alike.
// Prints each drive's mean and median update() time and mean debug_draw() time (us of the
// thread's CPU time: on a shared machine wall time would count other processes' turns), and
// checks that the three drives end with the same state hash.
//
//     bench_debug_draw [UPDATES]      (default 9000: 90 simulated seconds, about a lap)
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/gtc/quaternion.hpp>
#include <glm/mat3x3.hpp>

#include "trackphys/collision/mid_phase.hpp"
#include "trackphys/collision/static_collider.hpp"
#include "trackphys/track/track.hpp"
#include "trackphys/world/autopilot.hpp"
#include "trackphys/world/debug_draw.hpp"
#include "trackphys/world/world.hpp"

namespace {

using namespace trackphys;

// What a game's debug draw does at the least: reads every value it is handed.
class SummingDraw final : public DebugDraw {
  public:
    double sum = 0.0;
    std::size_t calls = 0;

  private:
    void draw_car(std::size_t, const Car& car) override { add(car.state().position.x); }
    void draw_ellipsoid(const DebugEllipsoid& e) override { add(e.shape.center().y); }
    void draw_contact(const DebugContact& c) override { add(c.contact.depth); }
    void draw_update_box(std::size_t, const Aabb& box) override { add(box.min.x); }
    void draw_listed_triangle(const DebugTriangle& t) override { add(t.triangle[0].x); }
    void draw_kept_triangle(const DebugTriangle& t, double bound) override {
        add(t.triangle[0].x + bound);
    }
    void add(double x) { sum += x, ++calls; }
};

struct Drive {
    std::string name;
    std::unique_ptr<World> world;
    Autopilot pilot;
    std::optional<DebugDrawOptions> drawn;  // none: never drawn
    SummingDraw draw;
    std::vector<double> update_us, draw_us;
};

// This thread's CPU time (us).
double thread_cpu_us() {
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return static_cast<double>(t.tv_sec) * 1e6 + static_cast<double>(t.tv_nsec) * 1e-3;
}

double mean(const std::vector<double>& v) {
    double sum = 0.0;
    for (double x : v) sum += x;
    return v.empty() ? 0.0 : sum / static_cast<double>(v.size());
}

double median(std::vector<double> v) {
    if (v.empty()) return 0.0;
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
    return v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
    const int updates = argc > 1 ? std::atoi(argv[1]) : 9000;
    TrackParams params;
    params.seed = kDemoTrackSeed;
    const Track track = generate_track(params);
    auto statics = std::make_shared<StaticWorld>();
    for (const TrackChunk& chunk : track.chunks)
        statics->add(std::make_shared<StaticCollider>(chunk.mesh));
    const ColliderPlaneTrees trees = make_collider_plane_trees(*statics);

    const CarSpec spec = CarSpec::default_car();
    const CenterlineSample& start = track.centerline.front();
    RigidBodyState state;
    state.position = start.position + start.up * (spec.lowest_point_depth() + 0.001);
    state.orientation =
        glm::normalize(glm::quat_cast(glm::dmat3(start.left, start.up, start.tangent)));

    std::vector<Drive> drives;
    // Profiled, as trackphys drive runs (the library's default is off).
    WorldSettings settings;
    settings.profile = true;
    const auto add_drive = [&](std::string name, std::optional<DebugDrawOptions> drawn) {
        auto world = std::make_unique<World>(statics, settings, trees);
        world->add_car(spec, state);
        drives.push_back(
            {std::move(name), std::move(world), Autopilot(track, spec), drawn, {}, {}, {}});
    };
    add_drive("not drawn", std::nullopt);
    add_drive("drawn, default options", DebugDrawOptions{});
    add_drive("drawn, every option", DebugDrawOptions::all());

    // Blocks of 10 updates, each block starting with the next drive: no drive always runs
    // right after the same other one. A debug_draw takes about a microsecond, as long as
    // reading the thread's clock, so each is timed as the mean of 100 back-to-back calls.
    constexpr int kBlock = 10;
    constexpr int kDrawRepeats = 100;
    for (int done = 0, block = 0; done < updates; done += kBlock, ++block)
        for (std::size_t turn = 0; turn < drives.size(); ++turn) {
            Drive& d = drives[(static_cast<std::size_t>(block) + turn) % drives.size()];
            for (int i = done; i < std::min(done + kBlock, updates); ++i) {
                Car& car = d.world->car(0);
                car.set_inputs(d.pilot.drive(car));
                double t = thread_cpu_us();
                d.world->update();
                d.update_us.push_back(thread_cpu_us() - t);
                if (!d.drawn) continue;
                t = thread_cpu_us();
                for (int r = 0; r < kDrawRepeats; ++r) d.world->debug_draw(d.draw, *d.drawn);
                d.draw_us.push_back((thread_cpu_us() - t) / kDrawRepeats);
            }
        }

    std::printf("%d updates of the default car on the default track, 3 drives in turns\n", updates);
    std::printf("%-24s %12s %14s %14s %12s\n", "drive", "update mean", "update median", "draw mean",
                "calls/draw");
    for (const Drive& d : drives)
        std::printf("%-24s %9.2f us %11.2f us %11.2f us %12.1f\n", d.name.c_str(),
                    mean(d.update_us), median(d.update_us), mean(d.draw_us),
                    d.draw_us.empty() ? 0.0
                                      : static_cast<double>(d.draw.calls) /
                                            static_cast<double>(d.draw_us.size() * kDrawRepeats));
    const double base = mean(drives[0].update_us);
    for (std::size_t k = 1; k < drives.size(); ++k)
        std::printf("update mean, %s / not drawn: %.3f\n", drives[k].name.c_str(),
                    mean(drives[k].update_us) / base);
    bool same = true;
    for (const Drive& d : drives)
        same = same && d.world->state_hash() == drives[0].world->state_hash();
    std::printf("state hashes %s (%016llx)\n", same ? "equal" : "DIFFER",
                static_cast<unsigned long long>(drives[0].world->state_hash()));
    return same ? 0 : 1;
}
