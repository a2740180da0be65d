#pragma once

#include <cstdint>
#include <span>

#include <glm/vec3.hpp>

#include "trackphys/collision/static_collider.hpp"
#include "trackphys/geometry/contact.hpp"
#include "trackphys/math/types.hpp"

namespace trackphys {

/// Two cars started touching during the update (docs/design.md#contact-events): the first
/// sub-step at which an ellipsoid of one overlapped an ellipsoid of the other. A touch that
/// goes on across save_state / restore_state does not begin again (WorldSnapshot::touching).
struct CarTouchBeginEvent {
    std::uint32_t car_a = 0;  ///< the lower car index
    std::uint32_t car_b = 0;  ///< the higher car index
    /// The deepest ellipsoid pair's contact at that sub-step: its point (m, world), its unit
    /// normal (moving car_a along it separates the cars) and its depth (m, > 0).
    glm::dvec3 point{0.0};
    glm::dvec3 normal{0.0, 1.0, 0.0};
    double depth = 0.0;
    /// How fast the cars closed along the normal at that point before the contact pushed
    /// them (m/s; > 0 approaching): the impact speed a crash sound or damage model wants.
    double approach_speed = 0.0;
};

/// Two cars stopped touching during the update: at its last sub-step no ellipsoid of one
/// overlapped the other. A touch that begins and ends within one update gives both events.
struct CarTouchEndEvent {
    std::uint32_t car_a = 0;  ///< the lower car index
    std::uint32_t car_b = 0;  ///< the higher car index
    double deepest = 0.0;     ///< the deepest overlap over the whole touch (m)
};

/// A body ellipsoid (EllipsoidRole::body, not a wheel) started touching the static world
/// during the update: at a sub-step its deepest contact was an overlap after one that was
/// not. At most one per ellipsoid and update (its first); a touch that goes on over later
/// updates gives none, unless World::teleport_car moved the car (its touches start afresh).
struct BodyHitEvent {
    std::uint32_t car = 0;
    std::uint32_t ellipsoid = 0;       ///< index into the car's CarSpec::ellipsoids
    TriangleRef triangle;              ///< the triangle of the deepest contact
    glm::dvec3 point{0.0};             ///< contact point (m, world)
    glm::dvec3 normal{0.0, 1.0, 0.0};  ///< unit, out of the triangle towards the car
    double depth = 0.0;                ///< overlap at that sub-step (m, > 0)
    /// How fast the body point moved into the triangle along the normal (m/s; > 0 into it).
    double approach_speed = 0.0;
};

/// Two cars touching at the last sub-step of the last update (World::car_contacts): the
/// deepest of their overlapping ellipsoid pairs.
struct CarPairContact {
    std::uint32_t car_a = 0;        ///< the lower car index
    std::uint32_t car_b = 0;        ///< the higher car index
    std::uint32_t ellipsoid_a = 0;  ///< car_a's ellipsoid (index into its CarSpec::ellipsoids)
    std::uint32_t ellipsoid_b = 0;  ///< car_b's ellipsoid
    /// Their contact as ellipsoid_ellipsoid_contact gives it, found before the sub-step's
    /// integration: point (m, world), unit normal (moving car_a along it separates the
    /// cars), depth (m, > 0).
    Contact contact{0.0, glm::dvec3(0.0, 1.0, 0.0), glm::dvec3(0.0)};
};

/// What touched what during the last World::update(), in an order that depends on the
/// inputs alone (not on threads or the job system): begins and ends by (car_a, car_b), hits
/// by car, each car's in the order they happened. Views into the World's buffers, valid
/// until its next update(), add_car, remove_car or restore_state.
struct ContactEvents {
    std::span<const CarTouchBeginEvent> car_touch_begins;
    std::span<const CarTouchEndEvent> car_touch_ends;
    std::span<const BodyHitEvent> body_hits;
};

}  // namespace trackphys
