#include "trackphys/world/world.hpp"

#include <algorithm>
#include <cstring>
#include <limits>
#include <utility>

#include <glm/geometric.hpp>

#include "trackphys/error.hpp"
#include "trackphys/geometry/contact.hpp"
#include "trackphys/geometry/ellipsoid_cull.hpp"

namespace trackphys {

World::World(std::shared_ptr<const StaticWorld> statics, WorldSettings settings)
    : statics_(std::move(statics)), settings_(std::move(settings)) {
    if (!statics_) throw Error("World: the static world is null");
    if (std::string why = settings_.validate(); !why.empty()) throw Error(why);
}

std::size_t World::add_car(const CarSpec& spec, const RigidBodyState& state) {
    CarSlot slot{Car(spec, state), {}, {}, {}, {}, {}, {}};
    slot.kept.resize(slot.car.ellipsoid_count());
    slot.deepest.resize(slot.car.ellipsoid_count());
    cars_.push_back(std::move(slot));
    return cars_.size() - 1;
}

void World::update() {
    profile_ = UpdateProfile{};
    const auto start = PhaseStopwatch::Clock::now();
    PhaseStopwatch watch(profile_, settings_.profile, trace_);
    for (CarSlot& slot : cars_) update_car(slot, watch);
    ++updates_;
    if (settings_.profile) {
        const auto end = PhaseStopwatch::Clock::now();
        profile_.update_us = std::chrono::duration<double, std::micro>(end - start).count();
        if (trace_) trace_->record("update", start, end);
    }
}

void World::update_car(CarSlot& slot, PhaseStopwatch& watch) {
    gather_candidates(slot);
    watch.lap(Phase::broad);
    const int substeps = settings_.steps * settings_.substeps;
    for (int s = 0; s < substeps; ++s) substep(slot, watch);
}

// The broad phase: every triangle a car can touch during this update. The car's box is the
// union of its ellipsoids' boxes, swept by its velocity over the update and padded by what
// rotation and a changing velocity can add.
void World::gather_candidates(CarSlot& slot) {
    const Car& car = slot.car;
    Aabb box;
    for (std::size_t i = 0; i < car.ellipsoid_count(); ++i) box.expand(car.world_ellipsoid(i).bounds());
    const double dt = settings_.dt_update;
    const RigidBodyState& state = car.state();
    // Any body point moves at most |omega| R dt by rotation; gravity alone bends the path by
    // |g| dt^2 / 2.
    const double margin = settings_.broad_phase_margin +
                          glm::length(state.angular_velocity) * car.bounding_radius() * dt +
                          0.5 * glm::length(settings_.gravity) * dt * dt;
    slot.candidates.clear();
    statics_->query_aabb(swept_box(box, state.linear_velocity * dt, margin), slot.candidates);

    slot.triangles.clear();
    slot.normalized.clear();
    for (const TriangleRef& ref : slot.candidates) {
        const StaticCollider& collider = statics_->collider(ref.collider);
        slot.triangles.push_back(collider.triangle(ref.triangle));
        slot.normalized.push_back(collider.normalized_triangle(ref.triangle));
    }
    profile_.candidates += slot.candidates.size();
}

void World::substep(CarSlot& slot, PhaseStopwatch& watch) {
    Car& car = slot.car;
    const std::size_t ellipsoids = car.ellipsoid_count();
    const std::size_t candidates = slot.normalized.size();

    // Cull: each ellipsoid's bounding sphere against every candidate's cheap frame test,
    // then the ellipsoid's own extent along the survivors' frame axes, which also bounds
    // how deep each survivor can be.
    slot.placed.clear();
    for (std::size_t i = 0; i < ellipsoids; ++i) {
        slot.placed.push_back(car.world_ellipsoid(i));
        const Ellipsoid& ellipsoid = slot.placed.back();
        const double radius = ellipsoid.bounding_radius();
        std::vector<Survivor>& kept = slot.kept[i];
        kept.clear();
        for (std::uint32_t c = 0; c < candidates; ++c) {
            if (!slot.normalized[c].may_touch_sphere(ellipsoid.center(), radius)) continue;
            const double bound = ellipsoid_depth_bound(slot.normalized[c], ellipsoid);
            if (bound > 0.0) kept.push_back({c, bound});
        }
    }
    profile_.culled_tests += ellipsoids * candidates;
    profile_.ellipsoid_substeps += ellipsoids;
    watch.lap(Phase::cull);

    // Exact contact: the deepest over each ellipsoid's survivors. The survivor with the
    // deepest bound goes first; after it, only survivors whose bound beats the deepest
    // contact found so far can change the answer.
    for (std::size_t i = 0; i < ellipsoids; ++i) {
        Contact& deepest = slot.deepest[i];
        deepest.depth = -std::numeric_limits<double>::infinity();
        std::vector<Survivor>& kept = slot.kept[i];
        if (kept.empty()) continue;
        std::iter_swap(kept.begin(), std::max_element(kept.begin(), kept.end(),
                                                      [](const Survivor& a, const Survivor& b) {
                                                          return a.depth_bound < b.depth_bound;
                                                      }));
        for (const Survivor& s : kept) {
            if (!(s.depth_bound > deepest.depth)) continue;
            const Contact contact = ellipsoid_triangle_contact(slot.placed[i], slot.triangles[s.candidate]);
            ++profile_.exact_tests;
            if (contact.depth > deepest.depth) deepest = contact;
        }
        profile_.contacts += deepest.depth > 0.0;
    }
    watch.lap(Phase::exact);

    car.resolve_deep_contacts(slot.deepest);
    const Wrench wrench = car.contact_wrench(slot.deepest);
    car.update_suspension(slot.deepest, settings_.substep_dt());
    car.integrate(wrench, settings_.gravity, settings_.substep_dt());
    watch.lap(Phase::integrate);
}

namespace {

// FNV-1a over raw bytes: the hash sees every bit of every double.
struct Fnv1a {
    std::uint64_t value = 0xcbf29ce484222325ull;
    void add(const void* data, std::size_t size) {
        const auto* bytes = static_cast<const unsigned char*>(data);
        for (std::size_t i = 0; i < size; ++i) value = (value ^ bytes[i]) * 0x100000001b3ull;
    }
    void add(double x) { add(&x, sizeof x); }
    void add(const glm::dvec3& v) { add(v.x), add(v.y), add(v.z); }
};

}  // namespace

std::uint64_t World::state_hash() const {
    Fnv1a hash;
    hash.add(&updates_, sizeof updates_);
    for (const CarSlot& slot : cars_) {
        const RigidBodyState& s = slot.car.state();
        hash.add(s.position);
        hash.add(s.orientation.w), hash.add(s.orientation.x), hash.add(s.orientation.y),
            hash.add(s.orientation.z);
        hash.add(s.linear_velocity);
        hash.add(s.angular_velocity);
        for (std::size_t i = 0; i < slot.car.ellipsoid_count(); ++i) hash.add(slot.car.suspension(i));
        const CarInputs& in = slot.car.inputs();
        hash.add(in.throttle), hash.add(in.brake), hash.add(in.steer);
    }
    return hash.value;
}

}  // namespace trackphys
