#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "trackphys/collision/static_collider.hpp"
#include "trackphys/collision/static_world.hpp"
#include "trackphys/dynamics/car.hpp"
#include "trackphys/dynamics/car_spec.hpp"
#include "trackphys/dynamics/rigid_body.hpp"
#include "trackphys/export.hpp"
#include "trackphys/geometry/contact.hpp"
#include "trackphys/world/world_settings.hpp"

namespace trackphys {

/// What a snapshot remembers of one static collider, to recognise it without a copy.
struct ColliderFingerprint {
    std::uint64_t mesh_triangles = 0;  ///< StaticCollider::mesh_triangle_count()
    std::uint64_t kept_triangles = 0;  ///< StaticCollider::triangle_count()
    std::uint64_t content_hash = 0;    ///< StaticCollider::content_hash()

    bool operator==(const ColliderFingerprint&) const = default;
};

/// The fingerprint of every collider of a static world, in id order: O(colliders), since
/// each collider hashed its triangles when it was built.
TRACKPHYS_API std::vector<ColliderFingerprint> fingerprint(const StaticWorld& statics);

/// A hash of every field of the spec (bits of every double): equal for equal specs.
TRACKPHYS_API std::uint64_t fingerprint(const CarSpec& spec);

/// One car's part of a WorldSnapshot: everything of the car and of its slot in the World
/// that a later update reads.
struct CarSnapshot {
    std::uint64_t spec_fingerprint = 0;  ///< fingerprint(CarSpec) of the car's spec
    RigidBodyState state;
    CarInputs inputs;
    /// Per ellipsoid, in CarSpec order (all three the same length):
    std::vector<double> suspension;  ///< Car::suspension(i), m
    /// The deepest contact of the last sub-step (World::contacts; depth -infinity for none).
    std::vector<Contact> contacts;
    /// The triangle of the deepest exact result, touching or not, which the next sub-step
    /// tests first: it decides the order of the exact tests, so it is state too. {~0u, ~0u}
    /// for none.
    std::vector<TriangleRef> deepest_refs;
    /// Bit i: ellipsoid i's last mid-phase list was empty. It sets how far the next
    /// update's first query looks ahead (LookAheadList::steps_ahead), so which triangles,
    /// and in which order, the next sub-steps test: state too. All bits set before a car's
    /// first update.
    std::uint64_t empty_lists = ~std::uint64_t{0};
    std::uint64_t resets = 0;  ///< World::car_resets
    /// Wheel spins and slips, gear, shift and clutch of a car with a vehicle model
    /// (Car::vehicle); empty for the arcade car.
    std::optional<VehicleState> vehicle;
};

/// A pair of cars touching at the end of the last update: the next update's begin and end
/// events (World::contact_events) are told apart against these, so a restored world gives
/// the events the saved one would have given (docs/design.md#contact-events).
struct CarTouchSnapshot {
    std::uint32_t car_a = 0;  ///< the lower car index
    std::uint32_t car_b = 0;  ///< the higher car index
    double deepest = 0.0;     ///< the deepest overlap since the touch began (m, >= 0)

    bool operator==(const CarTouchSnapshot&) const = default;
};

/// The complete dynamic state of a World: restore_state() of it, then update(), gives
/// bit-identical results to never having saved. The static world is referenced by its
/// fingerprint, never copied; a few hundred bytes per car.
///
/// Not part of it: the per-phase profile of the last update and the trace recorder (they
/// describe what the World object did, not the simulation), and each car's last reset
/// reason (the count is kept).
struct TRACKPHYS_API WorldSnapshot {
    std::vector<ColliderFingerprint> colliders;  ///< of the World's static world
    /// The stepping settings (every field but `profile`, `threads`, `jobs` and `surfaces`
    /// must match on restore: the surface table is the environment, as
    /// Vehicle::set_road_grip is, and restores into whatever table the world has).
    WorldSettings settings;
    std::uint64_t update_count = 0;
    std::vector<CarSnapshot> cars;
    /// The pairs of cars touching at the end of the last update, by (car_a, car_b).
    std::vector<CarTouchSnapshot> touching;

    /// Empty when the snapshot is consistent on its own: valid settings, per-ellipsoid
    /// vectors of equal length, finite states with unit orientations, inputs in range and
    /// not NaN, non-negative finite suspension, no NaN in a contact, a touching list of
    /// pairs of its cars (car_a < car_b), sorted and unique, each deepest finite and >= 0.
    /// Otherwise the first
    /// problem, naming the car and the field. (What only the World can check, fingerprints
    /// and suspension travel, restore_state checks.)
    std::string validate() const;
};

}  // namespace trackphys
