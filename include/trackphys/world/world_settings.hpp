#pragma once

#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "trackphys/collision/mid_phase_mode.hpp"
#include "trackphys/export.hpp"
#include "trackphys/math/types.hpp"
#include "trackphys/world/job_system.hpp"
#include "trackphys/world/surface.hpp"

namespace trackphys {

/// How a World steps (docs/design.md#the-update-loop). The defaults are the
/// write-up's: 100 updates a second, 10 steps of 4 sub-steps, so h = 0.25 ms.
struct TRACKPHYS_API WorldSettings {
    double dt_update = 0.01;  ///< seconds per update()
    int steps = 10;           ///< steps per update
    int substeps = 4;         ///< sub-steps per step (integration steps)
    /// The largest gravity validate() accepts (m/s^2, 100,000 g): beyond it the update's
    /// margins, which square it, stop being finite.
    static constexpr double kMaxGravity = 1e6;
    glm::dvec3 gravity{0.0, -9.81, 0.0};  ///< m/s^2, world +Y is up
    /// Extra broad-phase padding (m) beyond what the car can move in one update.
    double broad_phase_margin = 0.05;
    /// How each step's candidates are found (see MidPhaseMode; the default was measured
    /// fastest by bench_midphase).
    MidPhaseMode mid_phase = kDefaultMidPhaseMode;
    /// Steps a mid-phase query covers (>= 1): it sweeps each ellipsoid along its velocity
    /// that far ahead with mid_phase_slack more margin (look_ahead), and the following steps
    /// of the update reuse its list while their own swept ellipsoid stays inside; a list
    /// that came back empty (a body above the road) looks to the end of the update
    /// (LookAheadList). 1 queries every step for that step alone, as the write-up's loop did.
    /// The default, half of the default update's steps, lists a wheel in two queries an
    /// update; looking further ahead saves fewer queries than its longer lists cost the
    /// sub-step cull, and shorter looks make more queries, each costing more than the
    /// triangles it spares the cull (docs/benchmarks.md).
    int mid_phase_look_ahead = 5;
    /// Extra margin (m, finite, >= 0) of a query that looks ahead, which a step's small
    /// deviations from the straight path (a turn, a bump) spend before a new query.
    double mid_phase_slack = 0.005;
    /// A car that ends an update faster than this (m/s; default twice the 1000 km/h design
    /// speed) is in an impossible state and is reset (World::update).
    double max_car_speed = 2000.0 / 3.6;
    /// Likewise for its angular speed (rad/s): 500 turns the car 0.125 rad per default
    /// sub-step, still integrated well, and is three times the hardest impact tried (a
    /// 1080 km/h vertical drop onto a corner: 155 rad/s; 1000 km/h into a wall: 8 rad/s).
    double max_car_angular_speed = 500.0;
    /// World::add_car rejects a car whose centre of mass is farther than this (m) from the
    /// box of every collider: a car placed far outside the map is a mistake (a wrong unit or
    /// frame) and would fall forever.
    double max_spawn_distance = 1000.0;
    /// The game's surface table, indexed by the triangles' SurfaceId (TriangleMesh::surfaces):
    /// each wheel and body ellipsoid drives with the grip of the triangle under its deepest
    /// contact, at each sub-step. Empty (the default): every surface is the dry road, grip 1,
    /// whatever ids the meshes carry. Otherwise World refuses a static world with a triangle
    /// whose id has no entry; at most 65536 entries.
    std::vector<Surface> surfaces;
    /// Threads World::update spreads the islands of cars over (>= 0, at most 256): 0 for
    /// the hardware's count, 1 to run on the calling thread alone. World starts its pool
    /// the first time an update has two islands. Results do not depend on it. The default
    /// is a game's: its own workers have the cores, and the pool's threads spin up to
    /// 100 us before they sleep; plug the game's job system in (`jobs`) or raise this for a
    /// big field. World also builds the colliders' plane trees on thread_count() threads.
    int threads = 1;
    /// A game's own job system; when plugged in, World uses it instead of its own threads
    /// (and `threads` is not used). Results do not depend on it.
    JobSystem jobs;
    /// Measure per-phase times in the UpdateProfile (reads the clock a few times per
    /// sub-step, a share of the update: docs/benchmarks.md); counts are kept either way.
    /// Off by default, as a game runs; trackphys's own tools turn it on.
    bool profile = false;

    /// `threads` with 0 resolved to the hardware's count (at least 1).
    int thread_count() const;

    /// The sub-step (integration) time h = dt_update / (steps * substeps), seconds.
    double substep_dt() const { return dt_update / (steps * substeps); }

    /// Empty when every field is in range; otherwise the problem, naming the field.
    std::string validate() const;
};

}  // namespace trackphys
