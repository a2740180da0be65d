// World::save_state / restore_state and the fingerprints that tie a snapshot to its world.

#include "trackphys/world/world_snapshot.hpp"

#include <bit>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>
#include <utility>

#include <glm/geometric.hpp>

#include "core/fnv1a.hpp"
#include "dynamics/car_access.hpp"
#include "trackphys/error.hpp"
#include "trackphys/math/types.hpp"
#include "trackphys/world/world.hpp"
#include "vehicle/vehicle_fingerprint.hpp"
#include "world/car_slot.hpp"
#include "world/update_work.hpp"

namespace trackphys {
namespace {

void add(core::Fnv1a& hash, const ContactMaterial& m) {
    hash.add(m.stiffness), hash.add(m.damping), hash.add(m.friction), hash.add(m.slip_speed);
}

// Every field of CarSpec goes into its fingerprint. The size checks fail to compile when a
// field is added, as a reminder to hash it too (then update the sizes).
static_assert(sizeof(CarSpec) == 792, "a new CarSpec field must join fingerprint(CarSpec)");
static_assert(sizeof(CarEllipsoid) == 88,
              "a new CarEllipsoid field must join fingerprint(CarSpec)");

std::string describe(const ColliderFingerprint& f) {
    std::ostringstream text;
    text << f.mesh_triangles << " mesh triangles, " << f.kept_triangles << " kept, content hash "
         << std::hex << f.content_hash;
    return text.str();
}

bool same(double x, double y) {
    return std::bit_cast<std::uint64_t>(x) == std::bit_cast<std::uint64_t>(y);
}

// The first stepping setting that differs, or empty. `profile`, `threads` and `jobs` do not
// change results; `surfaces` is the environment the cars drive in, like
// Vehicle::set_road_grip, which a snapshot neither carries nor compares.
static_assert(sizeof(WorldSettings) == 160,
              "a new WorldSettings field must join settings_difference and the snapshot file");
std::string settings_difference(const WorldSettings& a, const WorldSettings& b) {
    std::ostringstream why;
    if (!same(a.dt_update, b.dt_update))
        why << "dt_update " << exact_text(a.dt_update) << " vs " << exact_text(b.dt_update);
    else if (a.steps != b.steps)
        why << "steps " << a.steps << " vs " << b.steps;
    else if (a.substeps != b.substeps)
        why << "substeps " << a.substeps << " vs " << b.substeps;
    else if (!same(a.gravity.x, b.gravity.x) || !same(a.gravity.y, b.gravity.y) ||
             !same(a.gravity.z, b.gravity.z))
        why << "gravity";
    else if (!same(a.broad_phase_margin, b.broad_phase_margin))
        why << "broad_phase_margin " << exact_text(a.broad_phase_margin) << " vs "
            << exact_text(b.broad_phase_margin);
    else if (a.mid_phase != b.mid_phase)
        why << "mid_phase " << to_string(a.mid_phase) << " vs " << to_string(b.mid_phase);
    else if (a.mid_phase_look_ahead != b.mid_phase_look_ahead)
        why << "mid_phase_look_ahead " << a.mid_phase_look_ahead << " vs "
            << b.mid_phase_look_ahead;
    else if (!same(a.mid_phase_slack, b.mid_phase_slack))
        why << "mid_phase_slack " << exact_text(a.mid_phase_slack) << " vs "
            << exact_text(b.mid_phase_slack);
    else if (!same(a.max_car_speed, b.max_car_speed))
        why << "max_car_speed " << exact_text(a.max_car_speed) << " vs "
            << exact_text(b.max_car_speed);
    else if (!same(a.max_car_angular_speed, b.max_car_angular_speed))
        why << "max_car_angular_speed " << exact_text(a.max_car_angular_speed) << " vs "
            << exact_text(b.max_car_angular_speed);
    else if (!same(a.max_spawn_distance, b.max_spawn_distance))
        why << "max_spawn_distance " << exact_text(a.max_spawn_distance) << " vs "
            << exact_text(b.max_spawn_distance);
    return why.str();
}

ColliderFingerprint fingerprint(const StaticCollider& c) {
    return {c.mesh_triangle_count(), c.triangle_count(), c.content_hash()};
}

std::string car_problem(const CarSnapshot& car) {
    const RigidBodyState& s = car.state;
    if (!is_finite(s.position)) return "position is not finite";
    // As far as a collider may reach: beyond it the update's boxes lose their precision.
    if (!(glm::length(s.position) <= StaticCollider::kMaxCoordinate))
        return "position is farther than 1e18 m from the origin";
    if (!is_finite(s.orientation) || !(std::abs(glm::length(s.orientation) - 1.0) < 1e-6))
        return "orientation is not a finite unit quaternion";
    if (!is_finite(s.linear_velocity)) return "linear_velocity is not finite";
    if (!is_finite(s.angular_velocity)) return "angular_velocity is not finite";
    const CarInputs& in = car.inputs;
    if (!(in.throttle >= -1.0 && in.throttle <= 1.0)) return "throttle is not in [-1, 1]";
    if (!(in.brake >= 0.0 && in.brake <= 1.0)) return "brake is not in [0, 1]";
    if (!(in.steer >= -1.0 && in.steer <= 1.0)) return "steer is not in [-1, 1]";
    if (car.suspension.empty()) return "it has no ellipsoids";
    if (car.contacts.size() != car.suspension.size() ||
        car.deepest_refs.size() != car.suspension.size())
        return "its per-ellipsoid lists differ in length";
    for (std::size_t i = 0; i < car.suspension.size(); ++i) {
        if (!(std::isfinite(car.suspension[i]) && car.suspension[i] >= 0.0))
            return "ellipsoid " + std::to_string(i) + "'s suspension is not finite and >= 0";
        const Contact& c = car.contacts[i];
        // depth is -infinity for "no contact"; normal and point feed the next sub-step's
        // force laws even then (multiplied by zero), so they must be finite.
        if (std::isnan(c.depth) || c.depth == std::numeric_limits<double>::infinity() ||
            !is_finite(c.normal) || !is_finite(c.point))
            return "ellipsoid " + std::to_string(i) + "'s contact is not finite";
    }
    if (car.vehicle) {
        for (const WheelState& w : car.vehicle->wheels)
            if (!(std::isfinite(w.spin) && std::isfinite(w.slip_ratio) &&
                  std::isfinite(w.lateral_slip) && std::isfinite(w.road_torque)))
                return "a vehicle wheel's spin or slip is not finite";
        const int gear = car.vehicle->gear;
        if (!((gear >= 1 || gear == VehicleState::reverse_gear) &&
              std::isfinite(car.vehicle->shift_time_left) && car.vehicle->clutch >= 0.0 &&
              car.vehicle->clutch <= 1.0))
            return "the vehicle's gear, shift time or clutch is out of range";
    }
    return {};
}

// The touching list as CarTouches keeps it: pairs of the snapshot's cars, in (a, b) order.
// Names a pair only when it is wrong: a rollback validates every restore, and must not
// allocate for each pair in contact.
std::string touching_problem(const std::vector<CarTouchSnapshot>& touching, std::size_t cars) {
    for (std::size_t i = 0; i < touching.size(); ++i) {
        const CarTouchSnapshot& t = touching[i];
        std::string problem;  // empty: no allocation
        if (!(t.car_a < t.car_b))
            problem = "car_a is not below car_b";
        else if (t.car_b >= cars)
            problem = "the snapshot has " + std::to_string(cars) + " cars";
        else if (i > 0 && !(std::pair(touching[i - 1].car_a, touching[i - 1].car_b) <
                            std::pair(t.car_a, t.car_b)))
            problem = "not after the pair before it (sorted, unique)";
        else if (!(std::isfinite(t.deepest) && t.deepest >= 0.0))
            problem = "deepest is not finite and >= 0";
        if (!problem.empty())
            return "touching pair " + std::to_string(i) + " (cars " + std::to_string(t.car_a) +
                   ", " + std::to_string(t.car_b) + "): " + problem;
    }
    return {};
}

}  // namespace

std::vector<ColliderFingerprint> fingerprint(const StaticWorld& statics) {
    std::vector<ColliderFingerprint> out;
    out.reserve(statics.size());
    for (std::uint32_t id = 0; id < statics.size(); ++id)
        out.push_back(fingerprint(statics.collider(id)));
    return out;
}

std::uint64_t fingerprint(const CarSpec& spec) {
    core::Fnv1a hash;
    hash.add(spec.mass.mass), hash.add(spec.mass.principal_inertia);
    hash.add(static_cast<std::uint64_t>(spec.ellipsoids.size()));
    for (const CarEllipsoid& e : spec.ellipsoids) {
        hash.add(e.center), hash.add(e.semi_axes), hash.add(e.orientation);
        hash.add(static_cast<std::uint64_t>(e.role));
    }
    add(hash, spec.body_contact);
    add(hash, spec.wheel_contact);
    add(hash, spec.car_contact);
    hash.add(spec.rear_grip_factor);
    hash.add(spec.suspension.stiffness), hash.add(spec.suspension.damping),
        hash.add(spec.suspension.travel);
    for (const double x : {spec.max_drive_force, spec.front_drive_share, spec.traction_limit,
                           spec.max_drive_power, spec.max_brake_force, spec.front_brake_share,
                           spec.max_steer_angle, spec.deep_contact_fraction, spec.drag_area,
                           spec.downforce_area, spec.air_density, spec.max_reverse_speed})
        hash.add(x);
    if (spec.vehicle) hash.add(fingerprint(*spec.vehicle));
    return hash.value;
}

std::string WorldSnapshot::validate() const {
    if (std::string why = settings.validate(); !why.empty()) return why;
    for (std::size_t i = 0; i < cars.size(); ++i)
        if (std::string why = car_problem(cars[i]); !why.empty())
            return "car " + std::to_string(i) + ": " + why;
    return touching_problem(touching, cars.size());
}

WorldSnapshot World::save_state() const {
    WorldSnapshot snapshot;
    save_state(snapshot);
    return snapshot;
}

// Every vector is assigned over the one `into` has, whose room a snapshot of the same world
// already has: rollback netcode saves a state every frame.
void World::save_state(WorldSnapshot& into) const {
    into.colliders.resize(statics_->size());
    for (std::uint32_t id = 0; id < statics_->size(); ++id)
        into.colliders[id] = fingerprint(statics_->collider(id));
    into.settings = settings_;
    into.update_count = updates_;
    into.cars.resize(cars_.size());
    for (std::size_t i = 0; i < cars_.size(); ++i) {
        const CarSlot& slot = cars_[i];
        CarSnapshot& saved = into.cars[i];
        saved.spec_fingerprint = fingerprint(slot.car.spec());
        saved.state = slot.car.state();
        saved.inputs = slot.car.inputs();
        const std::span<const double> suspension = slot.car.suspension();
        saved.suspension.assign(suspension.begin(), suspension.end());
        saved.contacts.assign(slot.deepest.begin(), slot.deepest.end());
        saved.deepest_refs.assign(slot.deepest_ref.begin(), slot.deepest_ref.end());
        saved.empty_lists = slot.empty_lists;
        saved.resets = slot.resets;
        if (const Vehicle* vehicle = slot.car.vehicle())
            saved.vehicle = vehicle->state();  // into the engaged one's wheels, if any
        else
            saved.vehicle.reset();
    }
    work_->touches.save(into.touching);
}

// Everything is checked before anything changes, so a rejected snapshot leaves the World
// as it was; then each car is written in place (no copies of the cars, which allocate).
void World::restore_state(const WorldSnapshot& snapshot) {
    const auto reject = [](const std::string& why) { throw Error("World::restore_state: " + why); };
    if (std::string why = snapshot.validate(); !why.empty())
        reject("the snapshot is invalid: " + why);

    if (snapshot.colliders.size() != statics_->size())
        reject("the snapshot was made over " + std::to_string(snapshot.colliders.size()) +
               " colliders, this world has " + std::to_string(statics_->size()));
    for (std::uint32_t i = 0; i < statics_->size(); ++i) {
        const ColliderFingerprint ours = fingerprint(statics_->collider(i));
        if (!(snapshot.colliders[i] == ours))
            reject("collider " + std::to_string(i) + " differs: the snapshot's has " +
                   describe(snapshot.colliders[i]) + ", this world's " + describe(ours));
    }
    if (std::string why = settings_difference(snapshot.settings, settings_); !why.empty())
        reject("the world settings differ (snapshot vs this world): " + why);
    if (snapshot.cars.size() != cars_.size())
        reject("the snapshot has " + std::to_string(snapshot.cars.size()) + " cars, this world " +
               std::to_string(cars_.size()) + " (add the same cars first)");

    for (std::size_t i = 0; i < cars_.size(); ++i) {
        const CarSnapshot& saved = snapshot.cars[i];
        const Car& car = cars_[i].car;
        if (saved.spec_fingerprint != fingerprint(car.spec()))
            reject("car " + std::to_string(i) + " has another CarSpec than the snapshot's");
        if (saved.suspension.size() != car.ellipsoid_count())
            reject("car " + std::to_string(i) + " has " + std::to_string(car.ellipsoid_count()) +
                   " ellipsoids, the snapshot " + std::to_string(saved.suspension.size()));
        if (std::string why = impossible_state(saved.state); !why.empty())
            reject("car " + std::to_string(i) + ": " + why);
        // A touching ellipsoid's triangle is read for its surface (contact_surface, the
        // grip): it must be one of this world's.
        for (std::size_t e = 0; e < saved.contacts.size(); ++e) {
            const TriangleRef ref = saved.deepest_refs[e];
            if (saved.contacts[e].depth > 0.0 &&
                !(ref.collider < statics_->size() &&
                  statics_->collider(ref.collider).has_triangle(ref.triangle)))
                reject("car " + std::to_string(i) + ": ellipsoid " + std::to_string(e) +
                       " touches triangle " + std::to_string(ref.triangle) + " of collider " +
                       std::to_string(ref.collider) + ", which this world does not have");
        }
        try {
            detail::CarAccess::check_restore(car, saved.state, saved.inputs, saved.suspension);
            if (saved.vehicle.has_value() != (car.vehicle() != nullptr))
                throw Error(car.vehicle() ? "the snapshot has no vehicle state for its model"
                                          : "the snapshot has a vehicle state for an arcade car");
            if (saved.vehicle) car.check_vehicle_state(*saved.vehicle);
        } catch (const Error& e) {
            reject("car " + std::to_string(i) + ": " + e.what());
        }
    }

    // Checked above: nothing below throws.
    for (std::size_t i = 0; i < cars_.size(); ++i) {
        CarSlot& slot = cars_[i];
        const CarSnapshot& saved = snapshot.cars[i];
        detail::CarAccess::restore(slot.car, saved.state, saved.inputs, saved.suspension);
        if (saved.vehicle) slot.car.set_vehicle_state(*saved.vehicle);
        slot.deepest.assign(saved.contacts.begin(), saved.contacts.end());
        slot.deepest_ref.assign(saved.deepest_refs.begin(), saved.deepest_refs.end());
        slot.empty_lists = saved.empty_lists;
        slot.resets = saved.resets;
        slot.last_reset.clear();
    }
    updates_ = snapshot.update_count;
    work_->touches.restore(snapshot.touching);
    work_->body_hits.clear();
}

}  // namespace trackphys
