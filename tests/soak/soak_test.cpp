// The soak (CTest label "long", docs/testing.md, "Bad input and long runs"): long drives checked
// after every update. (a) One simulated hour of the default track by autopilot, the target speed
// changing every lap up to 1000 km/h. (b) Free driving on a real-world track mesh (TORCS's
// g-track-1, fetched by scripts/fetch_torcs_track.sh). After every update: the state is finite, the
// car is above the road (a ray straight down from its centre of mass hits the surface; on the
// generated track also its height above the road plane of the nearest centreline sample), inside
// the walls (lateral offset from the centreline), its energy within what the engine could have
// given it; and the process's memory stays flat.

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <optional>
#include <random>

#include <gtest/gtest.h>
#include <unistd.h>

#include <glm/geometric.hpp>

#include "drive_scene.hpp"
#include "tool_world_settings.hpp"
#include "trackphys/math/types.hpp"
#include "trackphys/world/autopilot.hpp"
#include "trackphys/world/world.hpp"

namespace trackphys {
namespace {

// Resident set size of this process (bytes), from /proc/self/statm's second field (pages).
double resident_bytes() {
    std::ifstream statm("/proc/self/statm");
    double pages_total = 0.0, pages_resident = 0.0;
    statm >> pages_total >> pages_resident;
    return pages_resident * static_cast<double>(::sysconf(_SC_PAGESIZE));
}

bool finite_state(const RigidBodyState& s) {
    return is_finite(s.position) && is_finite(s.orientation) && is_finite(s.linear_velocity) &&
           is_finite(s.angular_velocity);
}

// Distance from p straight down to the surface, nullopt when nothing is below.
std::optional<double> height_above_surface(const StaticWorld& statics, const glm::dvec3& p) {
    const auto hit =
        statics.raycast(p, glm::dvec3(0.0, -1.0, 0.0), std::numeric_limits<double>::infinity());
    if (!hit) return std::nullopt;
    return hit->hit.distance;
}

// Figures that every soak prints and checks.
struct SoakFigures {
    std::uint64_t updates = 0;
    double wall_s = 0.0;
    double max_speed_kmh = 0.0;
    double min_height_m = std::numeric_limits<double>::infinity();  // ray straight down
    double max_energy_gain_j =
        -std::numeric_limits<double>::infinity();  // per update, beyond the engine
    double rss_early_mb = 0.0;
    double rss_end_mb = 0.0;

    void print(const char* name) const {
        std::printf(
            "%s: %llu updates, %.1f s wall clock, max speed %.1f km/h, min height of the centre of "
            "mass "
            "above the surface %.3f m, max energy gain beyond the engine's work %.1f J per update, "
            "RSS %.1f MB early -> %.1f MB at the end\n",
            name, static_cast<unsigned long long>(updates), wall_s, max_speed_kmh, min_height_m,
            max_energy_gain_j, rss_early_mb, rss_end_mb);
    }
};

// Mechanical energy (J): kinetic (translation and rotation) plus potential in gravity.
double mechanical_energy(const Car& car, const glm::dvec3& gravity) {
    return kinetic_energy(car.state(), car.spec().mass) -
           car.spec().mass.mass * glm::dot(gravity, car.state().position);
}

// The checks shared by both soaks after each update; returns false (after recording a
// test failure) on the first one that fails, so a broken run stops at once.
class UpdateChecker {
  public:
    UpdateChecker(const World& world, SoakFigures& figures) : world_(world), figures_(figures) {
        energy_ = mechanical_energy(world.car(0), world.settings().gravity);
        speed_ = world.car(0).speed();
    }

    bool check() {
        const Car& car = world_.car(0);
        const double t = world_.time();
        if (!finite_state(car.state())) {
            ADD_FAILURE() << "non-finite state at t = " << t << " s";
            return false;
        }
        figures_.max_speed_kmh = std::max(figures_.max_speed_kmh, car.speed() * 3.6);
        const std::optional<double> height =
            height_above_surface(world_.statics(), car.state().position);
        if (!height) {
            ADD_FAILURE() << "no surface below the car at t = " << t << " s, position ("
                          << car.state().position.x << ", " << car.state().position.y << ", "
                          << car.state().position.z << ")";
            return false;
        }
        figures_.min_height_m = std::min(figures_.min_height_m, *height);
        // The engine's work over the update is at most min(F v, P) dt (drive force and power
        // limits, v the larger speed of the update); gravity is in the potential; contacts,
        // friction and drag only take energy out, up to what the springs stored (a few kJ at
        // the deepest landings), hence the allowance.
        const double energy = mechanical_energy(car, world_.settings().gravity);
        const CarSpec& spec = car.spec();
        const double speed = std::max(speed_, car.speed());
        const double engine = std::min(spec.max_drive_force * speed, spec.max_drive_power) *
                              world_.settings().dt_update;
        const double gain = energy - energy_ - engine;
        energy_ = energy;
        speed_ = car.speed();
        figures_.max_energy_gain_j = std::max(figures_.max_energy_gain_j, gain);
        if (gain > kSpringAllowanceJ) {
            ADD_FAILURE() << "the car gained " << gain
                          << " J beyond the engine's power in one update at t = " << t;
            return false;
        }
        return true;
    }

    static constexpr double kSpringAllowanceJ = 2.0e4;

  private:
    const World& world_;
    SoakFigures& figures_;
    double energy_;
    double speed_;
};

TEST(Soak, DefaultTrackOneSimulatedHourByAutopilotUpTo1000KmH) {
    constexpr double kSeconds = 3600.0;
    // Target speeds, one per lap, in turn (km/h).
    constexpr std::array<double, 6> kTargets = {1000.0, 250.0, 600.0, 800.0, 400.0, 1000.0};
    const cli::DriveScene scene = cli::make_track_scene(7);
    const Track& track = *scene.track;
    const CarSpec spec = CarSpec::default_car();
    World world(scene.statics, cli::tool_world_settings());
    world.add_car(spec, cli::start_on_track(track, spec));

    std::size_t lap = 0;
    const auto autopilot_for_lap = [&](std::size_t i) {
        AutopilotSettings settings;
        settings.target_speed = kTargets[i % kTargets.size()] / 3.6;
        return Autopilot(track, spec, settings);
    };
    Autopilot autopilot = autopilot_for_lap(lap);
    SoakFigures figures;
    UpdateChecker checker(world, figures);
    double min_plane_height = std::numeric_limits<double>::infinity(), max_lateral = 0.0;
    const double half_width = 0.5 * track.params.width_m;
    const auto wall_start = std::chrono::steady_clock::now();
    while (world.time() < kSeconds - 1e-9) {
        Car& car = world.car(0);
        car.set_inputs(autopilot.drive(car));
        world.update();
        autopilot.locate(car);
        if (!checker.check()) break;
        // Height above, and offset across, the road at the nearest centreline sample.
        const CenterlineSample& s = track.centerline[autopilot.nearest_sample()];
        const glm::dvec3 offset = car.state().position - s.position;
        min_plane_height = std::min(min_plane_height, glm::dot(offset, s.up));
        max_lateral = std::max(max_lateral, std::abs(glm::dot(offset, s.left)));
        if (min_plane_height <= 0.0 || max_lateral >= half_width) {
            ADD_FAILURE() << "the car left the road at t = " << world.time()
                          << " s: height above the road plane " << glm::dot(offset, s.up)
                          << " m, lateral offset " << glm::dot(offset, s.left) << " m";
            break;
        }
        if (autopilot.laps() > 0) autopilot = autopilot_for_lap(++lap);  // next lap, next target
        if (world.update_count() == 60000) figures.rss_early_mb = resident_bytes() / 1e6;  // 10 min
    }
    figures.wall_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
    figures.updates = world.update_count();
    figures.rss_end_mb = resident_bytes() / 1e6;
    figures.print("default track, 1 h");
    std::printf(
        "default track, 1 h: %zu laps, min height above the road plane %.3f m, max lateral offset "
        "%.3f m (walls at %.1f m)\n",
        lap, min_plane_height, max_lateral, half_width);
    EXPECT_NEAR(world.time(), kSeconds, 1e-6);
    EXPECT_GE(lap, 20u) << "an hour is more than twenty laps even at 250 km/h";
    // Steady driving allocates nothing: the hour's last 50 minutes add no memory (a page or
    // two of noise allowed).
    EXPECT_LT(figures.rss_end_mb - figures.rss_early_mb, 1.0);
}

TEST(Soak, RealWorldTrackMeshFreeDriving) {
    const char* mesh = std::getenv("TRACKPHYS_SOAK_MESH");
    if (mesh == nullptr || !std::ifstream(mesh)) {
        GTEST_SKIP() << "no real-world track mesh: set TRACKPHYS_SOAK_MESH (CTest does, after "
                        "scripts/fetch_torcs_track.sh)";
    }
    constexpr double kSeconds = 600.0;
    const cli::DriveScene scene = cli::make_mesh_scene(mesh);
    const CarSpec spec = CarSpec::default_car();
    World world(scene.statics, cli::tool_world_settings(), scene.plane_trees);
    // The car lands on whatever is below (0, 50, 0): on g-track-1, the road near the origin.
    world.add_car(spec, cli::spawn_on_surface(*scene.statics, spec, {0.0, 50.0, 0.0}, 90.0));

    // A driver that heads for random waypoints in the middle of the mesh (its box shrunk by
    // a third: the terrain ends at the box, and the car would fall off its edge) and changes
    // throttle and brake every 2 s (fixed seed): it accelerates, brakes, turns both ways,
    // climbs, and bumps into whatever stands in its way.
    Aabb bounds;  // the mesh's, over its 100 m colliders
    for (std::uint32_t id = 0; id < scene.statics->size(); ++id)
        bounds.expand(scene.statics->collider(id).bounds());
    const glm::dvec3 centre = 0.5 * (bounds.min + bounds.max),
                     reach = (bounds.max - bounds.min) / 3.0;
    std::mt19937 random(8);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const auto next_waypoint = [&] {
        return centre + glm::dvec3((2.0 * unit(random) - 1.0) * reach.x, 0.0,
                                   (2.0 * unit(random) - 1.0) * reach.z);
    };
    glm::dvec3 waypoint = next_waypoint();
    CarInputs inputs;
    SoakFigures figures;
    UpdateChecker checker(world, figures);
    const auto wall_start = std::chrono::steady_clock::now();
    while (world.time() < kSeconds - 1e-9) {
        Car& car = world.car(0);
        const RigidBodyState& state = car.state();
        glm::dvec3 to_waypoint = waypoint - state.position;
        to_waypoint.y = 0.0;
        if (glm::length(to_waypoint) < 20.0 || world.update_count() % 3000 == 0)
            waypoint = next_waypoint();
        if (world.update_count() % 200 == 0) {
            const bool braking = unit(random) < 0.2;
            inputs.throttle = braking ? 0.0 : 0.2 + 0.8 * unit(random);
            inputs.brake = braking ? unit(random) : 0.0;
        }
        // Steer towards the waypoint: +1 is full left (body +X), the angle seen from above.
        const glm::dvec3 forward = state.orientation * glm::dvec3(0.0, 0.0, 1.0);
        const glm::dvec3 left = state.orientation * glm::dvec3(1.0, 0.0, 0.0);
        const double angle =
            std::atan2(glm::dot(to_waypoint, left), glm::dot(to_waypoint, forward));
        inputs.steer = std::clamp(angle / 0.6, -1.0, 1.0);
        car.set_inputs(inputs);
        world.update();
        if (!checker.check()) break;
        if (world.update_count() == 6000) figures.rss_early_mb = resident_bytes() / 1e6;  // 1 min
    }
    figures.wall_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
    figures.updates = world.update_count();
    figures.rss_end_mb = resident_bytes() / 1e6;
    std::printf("real track: %s, %zu triangles\n", mesh, scene.triangle_count);
    figures.print("real track, 10 min");
    EXPECT_NEAR(world.time(), kSeconds, 1e-6);
    EXPECT_LT(figures.rss_end_mb - figures.rss_early_mb, 1.0);
}

}  // namespace
}  // namespace trackphys
