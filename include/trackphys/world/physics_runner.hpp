#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include "trackphys/dynamics/car.hpp"
#include "trackphys/export.hpp"
#include "trackphys/world/car_view.hpp"
#include "trackphys/world/runner_events.hpp"
#include "trackphys/world/world.hpp"

namespace trackphys {

namespace detail {
class RunnerEventLog;
}

/// A World on a physics thread of its own, the "fix your timestep" loop of a game: the
/// thread runs World::update every dt_update (in real time, or as fast as it can), applies
/// each car's inputs at the update they are stamped with, and after every update publishes
/// the last two states, from which a render thread reads an interpolated pose or view
/// (CarView: pose, velocities, wheels, engine) per car for any render time without locks
/// and without torn reads.
///
/// The cars published are those the world had when the runner was made (in index order),
/// and the runner's car numbers (set_inputs, pose, view) stay theirs: the render thread may
/// read the published states at any time, so they cannot grow or shrink. remove_car takes a
/// car out of the world between runs (its number then stays unused); run_to refuses a world
/// that world() has added a car to or removed one from behind the runner's back.
///
/// Threads: one game thread (start, run_to, stop, set_inputs, remove_car, world) and one
/// render thread (pose, view, published_update; const, but a second reader at once would
/// race with the first over the buffer they take turns on); the physics thread is the
/// runner's own; latest_update() from any thread. Each render call reads the newest frame,
/// so two calls may read two frames: take the render time from the game's clock, not from
/// published_update().
/// Inputs go through a mutex (a few per update); publishing is a lock-free triple buffer (the
/// render thread always reads a complete pair of states, the newest one published).
/// Poses and views are published for the render thread; the world's contact events and
/// resets, once keep_events(true), are kept for the game thread's take_events (crash
/// sounds, damage, a reset car's message). Contact surfaces and the rest of the World are
/// read through world() between runs.
class TRACKPHYS_API PhysicsRunner {
  public:
    /// Takes the world (with its cars). real_time: one update per dt_update of wall clock
    /// (after a stall, an update slower than dt_update, the thread catches up with the wall
    /// clock by running the missed updates back to back, so that a render time taken from
    /// the game's clock stays covered); otherwise as fast as possible. Publishes the world's
    /// current state at once.
    explicit PhysicsRunner(World world, bool real_time = true);
    /// Stops the thread.
    ~PhysicsRunner();
    PhysicsRunner(const PhysicsRunner&) = delete;
    PhysicsRunner& operator=(const PhysicsRunner&) = delete;

    /// Starts the physics thread, which runs until stop() or until the world has run
    /// `last_update` updates. Throws trackphys::Error when it runs already or the world's
    /// car count is no longer the runner's (see the class notes).
    void run_to(std::uint64_t last_update);
    /// run_to with no last update: the thread runs until stop().
    void start() { run_to(UINT64_MAX); }
    /// Stops the thread after the update it is in and waits for it; rethrows what stopped
    /// it, if an update threw.
    void stop();
    /// Waits until the thread has reached run_to's update (or stopped); rethrows as stop().
    void wait();
    /// Whether the physics thread is still updating (game thread): false once it reached
    /// run_to's update, was stopped or an update threw. A game that start()ed polls it to
    /// learn that the world stopped; the next run_to, remove_car or world() then rethrows
    /// what stopped it, once, as wait() does.
    bool running() const { return running_.load(std::memory_order_acquire); }

    /// Sets car `car`'s inputs from update number `update` on (the world's
    /// update_count() once that update has run: the next update after n runs is n + 1).
    /// Inputs stamped for an update that has run already apply at the next one and are
    /// counted by late_inputs(); on time, a recorded input stream replays bit-identically.
    /// Throws trackphys::Error for a car that does not exist or NaN inputs.
    void set_inputs(std::uint64_t update, std::size_t car, const CarInputs& inputs);
    /// Keeps (or stops keeping) the world's contact events and resets after each update for
    /// take_events, from the next update on (game thread). Off at first: a game that never
    /// takes them keeps nothing.
    void keep_events(bool keep) { keep_events_.store(keep, std::memory_order_relaxed); }
    /// Moves the events kept since the last call into `out` (game thread, while the physics
    /// thread runs or not): out's earlier contents are dropped and its capacity goes to the
    /// runner's next events, so that a game taking them every frame allocates nothing once
    /// the lists have grown. See RunnerEvents.
    void take_events(RunnerEvents& out);

    /// How many set_inputs calls came after their update had run (see set_inputs).
    std::uint64_t late_inputs() const { return late_inputs_.load(std::memory_order_relaxed); }

    /// The last published update number (render thread).
    std::uint64_t published_update() const;
    /// The newest published update number (the world's update_count() when it was
    /// published), for any thread. A game thread that stamps inputs by the physics' progress
    /// rather than by its own clock stamps them latest_update() + 2: update
    /// latest_update() + 1 may be running already, its inputs taken, and an input stamped for
    /// it would be late (late_inputs()), applied an update later than a replay applies it.
    std::uint64_t latest_update() const { return latest_update_.load(std::memory_order_acquire); }
    /// Car `car`'s pose at simulated time `t` (s), interpolated between the last two
    /// published states (linearly, and slerp for the orientation): the older state's pose
    /// at or before its time, the newer one's at or after its time (render thread). Throws
    /// trackphys::Error for no such car or a NaN time.
    CarPose pose(std::size_t car, double t) const;
    /// Car `car`'s view at simulated time `t` (s) between the last two published states, as
    /// pose() interpolates, into `out` (render thread; no allocation once `out` has held
    /// this car's wheels). The ends are the states' views exactly; in between, velocities,
    /// engine rpm and each wheel's position, suspension, steer, spin and spin angle are
    /// linear, each wheel's orientation is made from the interpolated body orientation and
    /// angles, and the gear is the newer state's. Throws trackphys::Error for no such car or
    /// a NaN time, as pose does.
    void view(std::size_t car, double t, CarView& out) const;
    /// The same, returned (allocates the wheels).
    CarView view(std::size_t car, double t) const {
        CarView out;
        view(car, t, out);
        return out;
    }

    /// Removes car `car` (a runner number) from the world between runs, as
    /// World::remove_car does, deterministically: the same removals after the same updates
    /// give the world's bits of a direct replay. The other cars keep their runner numbers
    /// (the world's indices past it move down one; world() shows those); the removed car's
    /// pending inputs are dropped, and from the frame published at once, pose() and view()
    /// of it throw trackphys::Error saying it was removed, as set_inputs does. Throws
    /// trackphys::Error while the thread runs, or for a car that does not exist or was
    /// removed already.
    void remove_car(std::size_t car);

    /// The world, only while the thread is not running (throws trackphys::Error then; a
    /// thread that has finished is joined first, and what stopped it rethrown, as wait()
    /// does). Its car indices are the runner's numbers until a car is removed (see
    /// remove_car).
    World& world();

  private:
    // A pair of consecutive published states.
    struct Frame {
        std::uint64_t update = 0;
        double previous_time = 0.0;
        double time = 0.0;
        std::vector<CarView> previous;
        std::vector<CarView> current;
        std::vector<std::uint8_t> removed;  // per runner number: 1 once remove_car took it
        // How far from previous_time to time simulated time t is (0..1, 1 for no span).
        double alpha(double t) const;
    };
    struct StampedInputs {
        std::uint64_t update;
        std::size_t car;
        CarInputs inputs;
    };

    // Throws trackphys::Error naming the caller for a car past the published ones.
    void check_car(std::size_t car, const char* caller) const;
    // Throws trackphys::Error naming the caller for a NaN render time.
    static void check_time(double t, const char* caller);
    // check_car, and that `removed` (a frame's or the game thread's) does not mark it.
    void check_present(std::size_t car, const std::vector<std::uint8_t>& removed,
                       const char* caller) const;
    // Joins a thread that has finished and rethrows what stopped it (as wait()); whether a
    // thread is still running.
    bool still_running();
    void loop(std::uint64_t last_update);
    void apply_due_inputs();
    void publish();
    // Publishes the last published pair again, with removed_ (remove_car).
    void republish();
    // Hands frames_[back_] to the render thread.
    void swap_back();
    // The render thread's newest frame (takes a fresher one if the physics thread left it).
    const Frame& front() const;

    World world_;
    std::size_t cars_;
    std::uint64_t roster_version_;  // the world's after the runner's last change to its cars
    // Per runner number: the car's world index, and whether remove_car took it. Written only
    // between runs (remove_car), so the physics thread reads them without a lock.
    std::vector<std::size_t> world_index_;
    std::vector<std::uint8_t> removed_;
    bool real_time_;
    std::thread thread_;
    std::atomic<bool> stopping_{false};
    std::atomic<bool> running_{false};  // set by run_to, cleared by the thread as it ends
    std::exception_ptr error_;          // written by the thread before it clears running_

    std::mutex inputs_mutex_;
    std::vector<StampedInputs> pending_;  // guarded by inputs_mutex_
    std::atomic<std::uint64_t> late_inputs_{0};
    std::atomic<std::uint64_t> latest_update_{0};  // beside the triple buffer, for any thread
    std::atomic<bool> keep_events_{false};
    std::unique_ptr<detail::RunnerEventLog> events_;

    // Triple buffer: the physics thread owns frames_[back_], the render thread
    // frames_[front_], and the third waits in middle_ (index | kFresh once it is new).
    static constexpr unsigned kFresh = 4;
    Frame frames_[3];
    unsigned back_ = 0;
    unsigned published_ = 0;               // the frame last handed over: read-only to both threads
    std::vector<CarView> last_published_;  // physics thread's
    double last_published_time_ = 0.0;
    mutable unsigned front_ = 2;
    mutable std::atomic<unsigned> middle_{1};
};

}  // namespace trackphys
