#include "world/runner_event_log.hpp"

#include <utility>

namespace trackphys::detail {

void RunnerEventLog::start(const World& world, std::span<const std::size_t> world_index,
                           std::span<const std::uint8_t> removed) {
    runner_of_world_.assign(world.car_count(), 0);
    resets_seen_.assign(world_index.size(), 0);
    resets_now_.reserve(world_index.size());  // so that following resets never allocates
    for (std::size_t r = 0; r < world_index.size(); ++r) {
        if (removed[r]) continue;
        runner_of_world_[world_index[r]] = static_cast<std::uint32_t>(r);
        resets_seen_[r] = world.car_resets(world_index[r]);
    }
}

void RunnerEventLog::collect(const World& world, std::span<const std::size_t> world_index,
                             std::span<const std::uint8_t> removed, bool keep) {
    const std::uint64_t update = world.update_count();
    // The reset counts first, outside the lock: only this thread touches them.
    resets_now_.clear();
    for (std::size_t r = 0; r < world_index.size(); ++r) {
        if (removed[r]) continue;
        const std::uint64_t resets = world.car_resets(world_index[r]);
        if (resets == resets_seen_[r]) continue;
        resets_seen_[r] = resets;
        resets_now_.push_back(static_cast<std::uint32_t>(r));
    }
    if (!keep) return;
    const ContactEvents events = world.contact_events();
    const auto runner = [&](std::uint32_t car) { return runner_of_world_[car]; };
    std::lock_guard lock(mutex_);
    for (CarTouchBeginEvent e : events.car_touch_begins) {
        e.car_a = runner(e.car_a);
        e.car_b = runner(e.car_b);
        kept_.car_touch_begins.push_back({update, e});
    }
    for (CarTouchEndEvent e : events.car_touch_ends) {
        e.car_a = runner(e.car_a);
        e.car_b = runner(e.car_b);
        kept_.car_touch_ends.push_back({update, e});
    }
    for (BodyHitEvent e : events.body_hits) {
        e.car = runner(e.car);
        kept_.body_hits.push_back({update, e});
    }
    for (const std::uint32_t r : resets_now_)
        kept_.resets.push_back({update, {r, world.last_reset_reason(world_index[r])}});
}

void RunnerEventLog::take(RunnerEvents& out) {
    out.clear();
    std::lock_guard lock(mutex_);
    std::swap(out, kept_);
}

}  // namespace trackphys::detail
