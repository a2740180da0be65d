#include "trackphys/world/physics_runner.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>
#include <system_error>
#include <utility>

#include "trackphys/error.hpp"
#include "world/car_views.hpp"
#include "world/runner_event_log.hpp"

namespace trackphys {
namespace {

std::vector<CarView> views_of(const World& world) {
    std::vector<CarView> views;
    for (std::size_t i = 0; i < world.car_count(); ++i)
        views.push_back(detail::sized_view(world.car(i)));
    return views;
}

}  // namespace

PhysicsRunner::PhysicsRunner(World world, bool real_time)
    : world_(std::move(world)),
      cars_(world_.car_count()),
      roster_version_(world_.roster_version()),
      world_index_(cars_),
      removed_(cars_, 0),
      real_time_(real_time),
      events_(std::make_unique<detail::RunnerEventLog>()) {
    for (std::size_t i = 0; i < cars_; ++i) world_index_[i] = i;
    // Every buffer starts as the current state (both ends of the pair), sized for the cars
    // (and each car for its wheels) so that publishing never allocates.
    last_published_ = views_of(world_);
    for (Frame& frame : frames_) {
        frame.update = world_.update_count();
        frame.previous_time = frame.time = world_.time();
        frame.previous = frame.current = last_published_;
        frame.removed = removed_;
    }
    last_published_time_ = world_.time();
    latest_update_.store(world_.update_count(), std::memory_order_relaxed);
}

PhysicsRunner::~PhysicsRunner() {
    stopping_.store(true);
    if (thread_.joinable()) thread_.join();
}

void PhysicsRunner::run_to(std::uint64_t last_update) {
    if (still_running()) throw Error("PhysicsRunner::run_to: the physics thread runs already");
    if (world_.roster_version() != roster_version_)
        throw Error(
            "PhysicsRunner::run_to: cars were added to or removed from world() since "
            "the runner last changed them (it publishes the " +
            std::to_string(cars_) +
            " cars it was made with: remove one with PhysicsRunner::remove_car, or make a new "
            "runner for another field)");
    stopping_.store(false);
    error_ = nullptr;
    events_->start(world_, world_index_, removed_);
    running_.store(true, std::memory_order_relaxed);
    try {
        thread_ = std::thread([this, last_update] { loop(last_update); });
    } catch (const std::system_error& e) {
        running_.store(false, std::memory_order_relaxed);  // no thread will clear it
        throw Error(std::string("PhysicsRunner::run_to: could not start the physics thread (") +
                    e.what() + ")");
    }
}

bool PhysicsRunner::still_running() {
    if (!thread_.joinable()) return false;
    if (running()) return true;
    wait();
    return false;
}

void PhysicsRunner::wait() {
    if (thread_.joinable()) thread_.join();
    if (error_) std::rethrow_exception(std::exchange(error_, nullptr));
}

void PhysicsRunner::stop() {
    stopping_.store(true);
    wait();
}

void PhysicsRunner::remove_car(std::size_t car) {
    if (still_running()) throw Error("PhysicsRunner::remove_car: the physics thread is running");
    check_present(car, removed_, "PhysicsRunner::remove_car");
    world_.remove_car(world_index_[car]);
    roster_version_ = world_.roster_version();
    removed_[car] = 1;
    for (std::size_t i = car + 1; i < cars_; ++i) --world_index_[i];
    {
        std::lock_guard lock(inputs_mutex_);
        std::erase_if(pending_, [car](const StampedInputs& s) { return s.car == car; });
    }
    republish();
}

void PhysicsRunner::take_events(RunnerEvents& out) { events_->take(out); }

World& PhysicsRunner::world() {
    if (still_running()) throw Error("PhysicsRunner::world: the physics thread is running");
    return world_;
}

void PhysicsRunner::set_inputs(std::uint64_t update, std::size_t car, const CarInputs& inputs) {
    check_present(car, removed_, "PhysicsRunner::set_inputs");
    if (std::isnan(inputs.throttle) || std::isnan(inputs.brake) || std::isnan(inputs.steer))
        throw Error("PhysicsRunner::set_inputs: NaN input for car " + std::to_string(car));
    std::lock_guard lock(inputs_mutex_);
    pending_.push_back({update, car, inputs});
}

// Inputs in stamp order (then in the order they were given), each applied before the
// update it is stamped with.
void PhysicsRunner::apply_due_inputs() {
    const std::uint64_t next = world_.update_count() + 1;
    std::lock_guard lock(inputs_mutex_);
    if (pending_.empty()) return;
    std::stable_sort(
        pending_.begin(), pending_.end(),
        [](const StampedInputs& a, const StampedInputs& b) { return a.update < b.update; });
    auto due = pending_.begin();
    for (; due != pending_.end() && due->update <= next; ++due) {
        if (due->update < next) late_inputs_.fetch_add(1, std::memory_order_relaxed);
        world_.car(world_index_[due->car]).set_inputs(due->inputs);
    }
    pending_.erase(pending_.begin(), due);
}

void PhysicsRunner::loop(std::uint64_t last_update) {
    using Clock = std::chrono::steady_clock;
    const auto dt = std::chrono::duration_cast<Clock::duration>(
        std::chrono::duration<double>(world_.settings().dt_update));
    auto due = Clock::now();
    try {
        while (!stopping_.load() && world_.update_count() < last_update) {
            if (real_time_) {
                due += dt;
                std::this_thread::sleep_until(due);
            }
            apply_due_inputs();
            world_.update();
            events_->collect(world_, world_index_, removed_,
                             keep_events_.load(std::memory_order_relaxed));
            publish();
        }
    } catch (...) {
        error_ = std::current_exception();
    }
    running_.store(false, std::memory_order_release);
}

void PhysicsRunner::publish() {
    Frame& frame = frames_[back_];
    // The pair is (the last published state, this one). Same sizes, down to the wheels: the
    // copies assign into storage the frames already hold, no allocation.
    frame.previous = last_published_;
    frame.previous_time = last_published_time_;
    const double dt = world_.settings().dt_update;
    // A removed car's entries keep its last published view, which nothing reads.
    for (std::size_t i = 0; i < cars_; ++i)
        if (!removed_[i])
            detail::take_view(world_.car(world_index_[i]), last_published_[i], dt,
                              frame.current[i]);
    last_published_ = frame.current;
    last_published_time_ = world_.time();
    frame.update = world_.update_count();
    frame.time = world_.time();
    frame.removed = removed_;
    swap_back();
    latest_update_.store(world_.update_count(), std::memory_order_release);
}

void PhysicsRunner::republish() {
    Frame& frame = frames_[back_];
    const Frame& last = frames_[published_];  // never back_: only the render thread reads it
    frame.update = last.update;
    frame.previous_time = last.previous_time;
    frame.time = last.time;
    frame.previous = last.previous;
    frame.current = last.current;
    frame.removed = removed_;
    swap_back();
}

void PhysicsRunner::swap_back() {
    published_ = back_;
    back_ = middle_.exchange(back_ | kFresh, std::memory_order_acq_rel) & ~kFresh;
}

const PhysicsRunner::Frame& PhysicsRunner::front() const {
    if (middle_.load(std::memory_order_acquire) & kFresh)
        front_ = middle_.exchange(front_, std::memory_order_acq_rel) & ~kFresh;
    return frames_[front_];
}

std::uint64_t PhysicsRunner::published_update() const { return front().update; }

void PhysicsRunner::check_car(std::size_t car, const char* caller) const {
    if (car >= cars_)
        throw Error(std::string(caller) + ": no car " + std::to_string(car) + ": the runner has " +
                    std::to_string(cars_) + (cars_ == 1 ? " car" : " cars"));
}

void PhysicsRunner::check_present(std::size_t car, const std::vector<std::uint8_t>& removed,
                                  const char* caller) const {
    check_car(car, caller);
    if (removed[car])
        throw Error(std::string(caller) + ": car " + std::to_string(car) +
                    " was removed (PhysicsRunner::remove_car)");
}

double PhysicsRunner::Frame::alpha(double t) const {
    const double span = time - previous_time;
    return span > 0.0 ? std::clamp((t - previous_time) / span, 0.0, 1.0) : 1.0;
}

// A NaN time would interpolate a NaN pose (std::clamp passes NaN through); infinite ones
// clamp to the ends like any time outside the pair.
void PhysicsRunner::check_time(double t, const char* caller) {
    if (std::isnan(t)) throw Error(std::string(caller) + ": the render time is NaN");
}

CarPose PhysicsRunner::pose(std::size_t car, double t) const {
    check_time(t, "PhysicsRunner::pose");
    const Frame& frame = front();
    check_present(car, frame.removed, "PhysicsRunner::pose");
    return detail::interpolate(frame.previous[car].pose, frame.current[car].pose, frame.alpha(t));
}

void PhysicsRunner::view(std::size_t car, double t, CarView& out) const {
    check_time(t, "PhysicsRunner::view");
    const Frame& frame = front();
    check_present(car, frame.removed, "PhysicsRunner::view");
    detail::interpolate(frame.previous[car], frame.current[car], frame.alpha(t), out);
}

}  // namespace trackphys
