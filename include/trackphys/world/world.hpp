#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "trackphys/collision/mid_phase_mode.hpp"
#include "trackphys/collision/static_world.hpp"
#include "trackphys/dynamics/car.hpp"
#include "trackphys/export.hpp"
#include "trackphys/geometry/contact.hpp"
#include "trackphys/profile/update_profile.hpp"
#include "trackphys/world/contact_events.hpp"
#include "trackphys/world/debug_draw.hpp"
#include "trackphys/world/surface.hpp"
#include "trackphys/world/world_settings.hpp"
#include "trackphys/world/world_snapshot.hpp"

namespace trackphys {

class PhaseStopwatch;
class TraceRecorder;

/// Static colliders (shared, immutable) and the cars that drive on them. update() runs
/// the loop of docs/design.md#the-update-loop for every car: broad phase over the whole
/// update, then steps x sub-steps of cull, exact contact, deepest contact per ellipsoid,
/// forces and integration.
///
/// Cars touch each other (see CarSpec::car_contact and docs/design.md#cars-between-cars).
/// Each update starts with a broad phase among the cars over their update boxes; cars whose
/// boxes overlap, directly or through others, form an island and step sub-step by sub-step
/// together; a lone car runs its whole update alone. Islands run on settings().threads
/// threads or on a plugged-in job system, and the results do not depend on either: same
/// inputs, same build -> bit-identical states (state_hash()), for any number of threads,
/// also across save_state/restore_state, and so are the contact events.
///
/// Reset policy: a car that ends an update in an impossible state (a non-finite position,
/// orientation or velocity, a speed above settings().max_car_speed or an angular speed above
/// settings().max_car_angular_speed) is put back where it was at the start of that update,
/// with zero linear and angular velocity, its suspension as it was then, no contacts and its
/// inputs kept; car_resets() counts it and last_reset_reason() says why. The start state was
/// checked when it was reached, so the reset state is always possible. The other cars are
/// not affected (in an island whose update stopped on an error, they keep the state they
/// had reached). A car that starts an update impossible, given a speed or spin beyond the
/// limits since the last one (Car::set_state, Car::apply_impulse), is reset at rest where it
/// is, before the update, and counted the same way.
///
/// Threads: a World is not thread-safe. While update() runs on one thread (its islands on
/// its own workers or the plugged-in job system), no other thread may call anything on the
/// World or on what it hands out: not a const getter (car(i).state(), contacts(),
/// state_hash(), last_profile()), not debug_draw() nor save_state(), which read the cars
/// update() is writing. Calls between updates from any one thread at a time are fine. A
/// game that renders while the physics runs gives the World to a PhysicsRunner: its physics
/// thread owns the World, the game thread stamps inputs (and removes cars) through it, and a
/// render thread reads interpolated poses and views of the published states without locks.
///
/// A World moved from (into a PhysicsRunner, say) holds no static world: it may only be
/// destroyed or assigned to; any other call is undefined (update() dereferences it).
class TRACKPHYS_API World {
  public:
    /// Throws trackphys::Error on a null static world, invalid settings or a triangle whose
    /// surface id is beyond a non-empty settings.surfaces. In the
    /// precomputed_tree mid-phase mode the colliders' plane trees are built here (the
    /// costliest part of making a World), on settings.thread_count() short-lived threads
    /// even with a job system plugged in, unless `trees` holds them already (one per
    /// collider, in id order, e.g. another world's plane_trees() or a baked map's; trees of
    /// another count, a null one, or one over another number of triangles than its collider
    /// keeps are refused).
    explicit World(std::shared_ptr<const StaticWorld> statics, WorldSettings settings = {},
                   ColliderPlaneTrees trees = {});
    ~World();
    World(World&&) noexcept;
    World& operator=(World&&) noexcept;

    /// The colliders' precomputed plane trees (empty unless the mode uses them), to share
    /// with other worlds over the same static world.
    const ColliderPlaneTrees& plane_trees() const { return *trees_; }

    const WorldSettings& settings() const { return settings_; }
    const StaticWorld& statics() const { return *statics_; }

    /// Adds a car; returns its index (0, 1, 2... in order). Throws trackphys::Error, naming
    /// the reason, for:
    /// - an invalid spec or state (see Car);
    /// - a spec whose road contact springs the sub-step cannot integrate stably
    ///   (h^2 k / m + 2 h c / m above 4 for the wheel_contact or body_contact stiffness k
    ///   and damping c at one of its ellipsoids, m a lower bound of the car's effective
    ///   mass there);
    /// - with a vehicle model, a spec whose explicit wheel-spin update the sub-step cannot
    ///   integrate (h^2 R^2 C / (I sigma) not below 4 + 2 h low_speed / sigma: wheel radius
    ///   R, wheel inertia I, the tyre's longitudinal slip stiffness C at ten nominal
    ///   loads and relaxation length sigma);
    /// - a suspension whose explicit travel update the sub-step cannot integrate
    ///   (h (k + k_t + 2 a) / c not below 2: its stiffness k and damping c, the
    ///   wheel_contact stiffness k_t, a vehicle model's anti-roll rate a of either axle);
    /// - a spec whose car_contact springs the sub-step cannot integrate stably against a car
    ///   already here (the same test with the two cars' mean car_contact on their pair's
    ///   effective mass: a lighter car, a stiffer material or a coarser sub-step);
    /// - a state the reset policy would reset (too fast, spinning too fast);
    /// - a car inside geometry (an ellipsoid deeper than half its smallest semi-axis into a
    ///   static triangle) or far outside the map (its centre of mass farther than
    ///   settings().max_spawn_distance from every collider's box; a world without
    ///   triangles has no map and accepts any position);
    /// - a car inside another car (an ellipsoid overlapping one of another car's by more
    ///   than 1 mm, which a resting contact never sinks: the spring between them would
    ///   throw the two apart).
    std::size_t add_car(const CarSpec& spec, const RigidBodyState& state);
    /// Moves car i to `state` (Car::set_state: a teleport, with the vehicle rolling at the
    /// new speed) after add_car's checks of where a car may be: throws trackphys::Error
    /// naming the reason, changing nothing, for a state the reset policy would reset, a
    /// car far outside the map, inside geometry or inside another car. car(i).set_state
    /// moves it unchecked.
    /// The suspension starts at full droop, as after add_car, so a car's own state from
    /// an update that compressed it can be refused (a squatting car's rear wheels hang
    /// 8 cm into the road at droop); place_car_on_surface gives a resting height.
    /// Its contacts start afresh: contacts(i) reads none until the next update, and a body
    /// ellipsoid touching the static world there gives a hit (contact_events), as after a
    /// reset; its touches with other cars go on (a pair apart after it ends at the next
    /// update).
    void teleport_car(std::size_t i, const RigidBodyState& state);
    /// Removes car i (a retirement, a player leaving) between updates. Indices work as
    /// std::vector::erase's: the cars before i keep theirs, each car after it moves down one
    /// (car j becomes j - 1), so a game that keeps a car's index drops it or decrements it
    /// past i; removing the last car changes no index. Every remaining car keeps everything
    /// (state, inputs, suspension, contacts, resets, reset reason, vehicle state), and
    /// update_count() and time() go on. Deterministic like update(): the same removals after
    /// the same updates give bit-identical states on any number of threads. Snapshots list
    /// the cars in index order: save_state() afterwards holds the remaining cars, which
    /// restore into a world of the same specs added in that order; a snapshot from before
    /// the removal has a car more and restore_state() refuses it. Throws trackphys::Error
    /// past car_count().
    void remove_car(std::size_t i);
    std::size_t car_count() const;
    /// How many add_car and remove_car calls the world has had: a holder of car indices
    /// (PhysicsRunner) keeps it to tell that the cars are still those it knows, which the
    /// count alone does not (a removal and an add leave it as it was).
    std::uint64_t roster_version() const { return roster_version_; }
    /// Car i (throws trackphys::Error past car_count(), as every call taking a car index
    /// does): the handle through which a game sets its inputs, moves it (Car::set_state,
    /// unchecked; teleport_car checks), sets its vehicle state or road grip
    /// (Car::vehicle()), pushes it (Car::apply_impulse) and reads its spec, state and
    /// telemetry. It cannot replace the car (Car is not assignable: the world keeps
    /// per-ellipsoid lists sized for the car add_car made; add another car instead), nor run
    /// the world's own steps on it (the sub-step, a snapshot's restore: private to Car and
    /// Vehicle, see Car's class notes), which would leave time() and contacts() behind it.
    Car& car(std::size_t i);
    const Car& car(std::size_t i) const;

    /// Car i's deepest contact per ellipsoid (in CarSpec order) at the last sub-step of
    /// the last update; where an ellipsoid touched nothing (or the car has not been updated
    /// since it was added, reset or teleported), depth -infinity and a zero normal and point.
    std::span<const Contact> contacts(std::size_t i) const;
    /// What ellipsoid `ellipsoid` (in CarSpec order) of car i touched at the last sub-step of
    /// the last update: the triangle of its deepest contact, contacts(i)[ellipsoid], and that
    /// triangle's surface id; nullopt where it touched nothing (depth <= 0). Throws
    /// trackphys::Error past car_count() or the car's ellipsoids.
    std::optional<ContactSurface> contact_surface(std::size_t i, std::size_t ellipsoid) const;

    /// Advances every car by settings().dt_update, resetting any car that ends it in an
    /// impossible state (see the class notes). Throws trackphys::Error, changing nothing,
    /// when a collider added to the static world since the last update (the mid-phase modes
    /// without precomputed trees allow it) has a surface id settings().surfaces has no entry
    /// for.
    void update();

    /// The pairs of cars touching at the last sub-step of the last update, by (car_a,
    /// car_b): each pair's deepest overlapping ellipsoid pair and its contact, what
    /// contacts(i) is for the road. The same for any number of threads or a job system.
    /// Empty until the next update after restore_state or remove_car (whose indices it would
    /// hold stale); teleport_car drops the moved car's pairs. A view into the World's
    /// buffer, valid until its next update(), add_car, remove_car, teleport_car or
    /// restore_state; a warm field allocates nothing for it.
    std::span<const CarPairContact> car_contacts() const;

    /// What touched what during the last update (docs/design.md#contact-events): cars that
    /// began or stopped touching each other, with where and how fast, and body ellipsoids
    /// that started touching the static world (wheels rolling on the road are not events).
    /// Read after update(); the same for any number of threads or a job system. A reset
    /// car touches nothing of the undone update: its hits are dropped, its pairs that were
    /// touching end, and a touch still there begins again at the next update. Which car
    /// pairs are touching is part of a snapshot (WorldSnapshot::touching): after
    /// restore_state the next update gives the events the saved world's would have given;
    /// remove_car forgets the removed car's touches (no end event) and drops the last
    /// update's events, whose indices are stale: contact_events() is empty until the next
    /// update. Recording them allocates nothing once a field is warm.
    ContactEvents contact_events() const;

    /// How many times car i was reset (counted over the whole simulation: snapshots keep it).
    std::uint64_t car_resets(std::size_t i) const;
    /// Why car i was last reset by this World object ("update N: speed ... m/s is above
    /// ..."), or empty.
    const std::string& last_reset_reason(std::size_t i) const;

    /// The complete dynamic state (see WorldSnapshot): a few hundred bytes per car.
    WorldSnapshot save_state() const;
    /// The same into `into`, reusing its vectors: saving into a snapshot already saved from
    /// this world (the same cars) allocates nothing, as rollback netcode saving every frame
    /// wants.
    void save_state(WorldSnapshot& into) const;
    /// Puts the world back into a saved state: the next update() gives bit-identical results
    /// to the world it was saved from. The world must have the same static colliders, the
    /// same stepping settings and the same cars (number and CarSpec, added in the same order;
    /// their current states do not matter). Throws trackphys::Error naming what differs or
    /// what is invalid, and then changes nothing. Checks everything first and then writes
    /// each car in place: it allocates nothing (but on error, or for more touching pairs than
    /// this world's lists ever held).
    void restore_state(const WorldSnapshot& snapshot);

    /// Simulated time (s) and number of updates run.
    double time() const { return static_cast<double>(updates_) * settings_.dt_update; }
    std::uint64_t update_count() const { return updates_; }

    /// What the last update did: per-phase times (if settings().profile) and counts.
    const UpdateProfile& last_profile() const { return profile_; }

    /// FNV-1a hash of the bits of the update count and of every car's rigid-body state,
    /// suspension travel, inputs and, with a vehicle model, vehicle state (wheel spins and
    /// slips, gear, clutch): equal hashes mean bit-identical simulations.
    std::uint64_t state_hash() const;

    /// Records each update's phases into trace while settings().profile is on (or stops, for
    /// nullptr); an update spread over several workers records only its broad phase and the
    /// update zone. The recorder must outlive its use here.
    void set_trace(TraceRecorder* trace) { trace_ = trace; }

    /// Shows the cars as the last update left them to `draw` (see DebugDraw for the calls and
    /// their order), as `options` selects. A pull: update() only keeps a copy of the
    /// triangles' refs for it (a few lines a car). The update boxes and triangle lists are
    /// the working memory of the last update this object ran for the car (none before the
    /// first; for a reset car, the undone update's; a snapshot does not hold them, so after
    /// restore_state they predate the restore).
    void debug_draw(DebugDraw& draw, const DebugDrawOptions& options = {}) const;

  private:
    // A car and its per-update working memory (src/world/car_slot.hpp): defined out of line so
    // that the mid phase and its lists stay out of every user's includes.
    struct CarSlot;
    // The update's islands, per-worker profiles and threads (src/world/update_work.hpp).
    struct UpdateWork;
    // A car's working memory that is dead between its updates (src/world/car_scratch.hpp).
    struct CarScratch;
    // A worker's memory for the cars it is updating (src/world/update_work.hpp).
    struct WorkerScratch;

    // Car i's slot; throws trackphys::Error naming i and car_count() past the last car.
    CarSlot& car_slot(std::size_t i);
    const CarSlot& car_slot(std::size_t i) const;
    void run_islands();
    void collect_contact_events();
    void check_given_trees(const ColliderPlaneTrees& trees) const;
    // The job-system task over the update's islands (context: the World).
    static void island_task(int begin, int end, int worker, void* world);
    // step_island under the reset policy (world_reset.cpp).
    void update_island_or_reset(std::size_t island, WorkerScratch& scratch, PhaseStopwatch& watch);
    // Throws naming the first triangle whose surface id settings_.surfaces has no entry for,
    // among the colliders not checked yet: the modes without precomputed trees let a game add
    // colliders after the World was made, and the sub-step reads the table unchecked.
    void check_new_surfaces();
    // Why this state breaks the reset policy's limits, or empty.
    std::string impossible_state(const RigidBodyState& state) const;
    // The reset policy for the cars made impossible between updates (world_reset.cpp).
    void reset_impossible_starts();
    // Puts the slot's car at `at` at rest with `suspension`, forgetting its contacts, and
    // counts the reset with its reason.
    void reset_at_rest(CarSlot& slot, RigidBodyState at, std::span<const double> suspension,
                       std::string reason);
    // add_car's checks of where the car is (world_placement.cpp), to be car `index` (the others
    // are the cars it must not be inside).
    void check_placement(const Car& car, const char* caller, std::size_t index) const;
    // add_car's check that the sub-step integrates the spec's contacts and wheel spins
    // stably (world_placement.cpp).
    void check_integrable(const CarSpec& spec) const;
    // A lone car runs its whole update alone; an island's cars sub-step together
    // (world_island.cpp).
    void step_island(std::size_t island, WorkerScratch& scratch, PhaseStopwatch& watch);
    void update_car(CarSlot& slot, const Aabb& box, PhaseStopwatch& watch);
    void begin_update(CarSlot& slot, const Aabb& box, PhaseStopwatch& watch);
    void list_step_candidates(CarSlot& slot, int steps_left, PhaseStopwatch& watch);
    static void place_ellipsoids(CarSlot& slot, bool every);
    void find_contacts(CarSlot& slot, PhaseStopwatch& watch);
    void advance(CarSlot& slot, PhaseStopwatch& watch);

    std::shared_ptr<const StaticWorld> statics_;
    WorldSettings settings_;
    std::shared_ptr<const ColliderPlaneTrees> trees_;  // never null; every car's MidPhase reads it
    std::vector<CarSlot> cars_;
    std::uint64_t roster_version_ = 0;
    std::size_t colliders_checked_ = 0;  // by check_new_surfaces
    std::unique_ptr<UpdateWork> work_;
    std::uint64_t updates_ = 0;
    UpdateProfile profile_;
    TraceRecorder* trace_ = nullptr;
};

}  // namespace trackphys
