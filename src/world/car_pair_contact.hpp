#pragma once

#include <cstdint>
#include <span>

#include "trackphys/dynamics/car.hpp"
#include "trackphys/geometry/contact.hpp"
#include "trackphys/geometry/ellipsoid.hpp"

namespace trackphys::detail {

/// What one sub-step of contact between two cars found.
struct CarPairTouch {
    std::uint64_t exact_tests = 0;  ///< ellipsoid pairs the cheap culls let through
    double deepest = 0.0;           ///< deepest overlap (m), 0 when they did not touch
    /// The deepest overlapping ellipsoid pair's contact (normal: moving a along it separates)
    /// and how fast the cars closed along its normal at its point before that pair pushed
    /// (m/s, > 0 approaching): for the contact events. Unset when they did not touch.
    Contact deepest_contact{0.0, glm::dvec3(0.0, 1.0, 0.0), glm::dvec3(0.0)};
    double approach_speed = 0.0;
    std::uint32_t deepest_a = 0;  ///< that pair's ellipsoid of a (CarSpec order)
    std::uint32_t deepest_b = 0;  ///< and of b
};

/// The material between two cars: the mean of their CarSpec::car_contact.
ContactMaterial mean_material(const ContactMaterial& a, const ContactMaterial& b);

/// One sub-step of h seconds of contact between cars a and b, whose ellipsoids in the
/// world are a_placed and b_placed (Car::world_ellipsoid, in CarSpec order). Each
/// overlapping ellipsoid pair pushes the two cars apart at its contact point, equally and
/// oppositely, as impulses of force times h (so the cars' integration that follows is
/// semi-implicit Euler under these forces):
/// - a pair the spring cannot hold within the smaller deep_contact_fraction of the cars
///   times the smaller ellipsoid's smallest semi-axis (already that deep, or closing so
///   fast that the spring would let it sink that deep), still approaching, first gets the
///   impulse that stops the approach at the point (plastic, as Car::advance does for the
///   road), with Coulomb friction of up to mu times it against the slip. A spring stiff enough to stop 1000 km/h within centimetres is not stable at
///   this sub-step, and deeper than an ellipsoid's thinnest half the least-translation
///   normal turns sideways and lets the cars through; so hard impacts are plastic along
///   the normal, as real crashes nearly are;
/// - then the spring-damper max(0, k d - c v_n) along the normal and regularised Coulomb
///   friction against the relative slip, with the mean of the two cars' car_contact
///   materials; the friction impulse is capped at what stops the slip, so a hard impact's
///   large normal force cannot reverse the slip.
/// The pairs are visited in order (a's ellipsoids, then b's), each seeing the velocities
/// the previous ones left: deterministic, and linear and angular momentum are conserved.
CarPairTouch touch_cars(Car& a, std::span<const Ellipsoid> a_placed, Car& b,
                        std::span<const Ellipsoid> b_placed, double h);

}  // namespace trackphys::detail
