#include "world/car_pair_contact.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>

#include <glm/geometric.hpp>

#include "dynamics/car_access.hpp"
#include "trackphys/dynamics/contact_force.hpp"
#include "trackphys/geometry/ellipsoid_pair.hpp"

namespace trackphys::detail {

ContactMaterial mean_material(const ContactMaterial& a, const ContactMaterial& b) {
    return {0.5 * (a.stiffness + b.stiffness), 0.5 * (a.damping + b.damping),
            0.5 * (a.friction + b.friction), 0.5 * (a.slip_speed + b.slip_speed)};
}

namespace {

glm::dvec3 relative_velocity(const RigidBodyState& a, const RigidBodyState& b,
                             const glm::dvec3& point) {
    return point_velocity(a, point) - point_velocity(b, point);
}

glm::dvec3 relative_velocity(const Car& a, const Car& b, const glm::dvec3& point) {
    return relative_velocity(a.state(), b.state(), point);
}

void push_apart(Car& a, Car& b, const glm::dvec3& impulse, const glm::dvec3& point) {
    detail::CarAccess::push(a, impulse, point);
    detail::CarAccess::push(b, -impulse, point);
}

// The plastic impulse for a contact the spring cannot hold within `budget` (m) of depth:
// one already deeper, or one closing so fast that the spring would let it sink deeper
// (a spring of stiffness k stops a closing speed v over v sqrt(m / k), m the pair's
// effective mass along the normal). The relative normal velocity at the point is brought
// to zero, and Coulomb friction takes up to mu times that impulse from the slip (without
// it, cars meeting at an angle above ~150 km/h slid off each other as if on ice).
void stop_if_too_deep(Car& a, Car& b, const Contact& contact, const ContactMaterial& material,
                      double budget) {
    const glm::dvec3 velocity = relative_velocity(a, b, contact.point);
    const double approach = glm::dot(velocity, contact.normal);
    if (approach >= 0.0) return;
    const double inverse_mass = a.inverse_mass_along(contact.normal, contact.point) +
                                b.inverse_mass_along(contact.normal, contact.point);
    const double sinking = -approach * std::sqrt(1.0 / (inverse_mass * material.stiffness));
    if (!(contact.depth + sinking > budget)) return;
    const double stopping = -approach / inverse_mass;
    glm::dvec3 impulse = contact.normal * stopping;
    const glm::dvec3 slip = velocity - contact.normal * approach;
    const double slip_speed = glm::length(slip);
    if (slip_speed > 0.0) {
        const glm::dvec3 along = slip / slip_speed;
        const double stops_slip = slip_speed / (a.inverse_mass_along(along, contact.point) +
                                                b.inverse_mass_along(along, contact.point));
        impulse -= along * std::min(material.friction * stopping, stops_slip);
    }
    push_apart(a, b, impulse, contact.point);
}

// Spring, damper and friction over h, as impulses.
void press(Car& a, Car& b, const Contact& contact, const ContactMaterial& material, double h) {
    const glm::dvec3 velocity = relative_velocity(a, b, contact.point);
    const double pressing = normal_force(material, contact.depth, contact.normal, velocity);
    if (pressing == 0.0) return;
    glm::dvec3 impulse = contact.normal * (pressing * h);
    const glm::dvec3 slip = velocity - contact.normal * glm::dot(velocity, contact.normal);
    const double slip_speed = glm::length(slip);
    if (slip_speed > 0.0) {
        const glm::dvec3 along = slip / slip_speed;
        const double regularised =
            material.friction * pressing * h * std::min(slip_speed / material.slip_speed, 1.0);
        const double stopping = slip_speed / (a.inverse_mass_along(along, contact.point) +
                                              b.inverse_mass_along(along, contact.point));
        impulse -= along * std::min(regularised, stopping);
    }
    push_apart(a, b, impulse, contact.point);
}

// The sphere about a car's centre of mass that holds its placed ellipsoids.
struct PlacedReach {
    glm::dvec3 center;
    double radius = 0.0;
};

PlacedReach placed_reach(const Car& car, std::span<const Ellipsoid> placed) {
    PlacedReach reach{car.state().position};
    for (const Ellipsoid& e : placed)
        reach.radius =
            std::max(reach.radius, glm::length(e.center() - reach.center) + e.bounding_radius());
    return reach;
}

static_assert(CarSpec::max_ellipsoids <= 64, "a car's ellipsoids are bits of one std::uint64_t");

// Bit i (a CarSpec holds at most 64 ellipsoids): ellipsoid i reaches into the other car's
// sphere, so it may touch one of its ellipsoids. The margin (far above rounding) keeps the
// test conservative: it leaves out only pairs that ellipsoids_may_touch would reject too.
std::uint64_t reaching(std::span<const Ellipsoid> placed, const PlacedReach& other) {
    constexpr double kMargin = 1e-6;  // m
    std::uint64_t mask = 0;
    for (std::size_t i = 0; i < placed.size(); ++i) {
        const glm::dvec3 apart = placed[i].center() - other.center;
        const double reach = placed[i].bounding_radius() + other.radius + kMargin;
        if (!(glm::dot(apart, apart) > reach * reach)) mask |= std::uint64_t{1} << i;
    }
    return mask;
}

}  // namespace

CarPairTouch touch_cars(Car& a, std::span<const Ellipsoid> a_placed, Car& b,
                        std::span<const Ellipsoid> b_placed, double h) {
    CarPairTouch touch;
    const double reach = a.bounding_radius() + b.bounding_radius();
    const glm::dvec3 apart = a.state().position - b.state().position;
    if (glm::dot(apart, apart) > reach * reach) return touch;

    const ContactMaterial material = mean_material(a.spec().car_contact, b.spec().car_contact);
    const double deep_fraction =
        std::min(a.spec().deep_contact_fraction, b.spec().deep_contact_fraction);
    // Cars queued nose to tail are within reach of each other with most of their
    // ellipsoids far apart: each car's ellipsoids against the other's sphere first, so
    // only the few pairs near the gap meet the ellipsoid pair's own culls.
    const std::uint64_t a_reaching = reaching(a_placed, placed_reach(b, b_placed));
    const std::uint64_t b_reaching = reaching(b_placed, placed_reach(a, a_placed));
    // The approach speed is the cars' before any pair of this sub-step pushed them.
    const RigidBodyState a_before = a.state();
    const RigidBodyState b_before = b.state();
    for (std::size_t i = 0; i < a_placed.size(); ++i) {
        if (!(a_reaching >> i & 1)) continue;
        const Ellipsoid& ea = a_placed[i];
        for (std::size_t j = 0; j < b_placed.size(); ++j) {
            if (!(b_reaching >> j & 1)) continue;
            const Ellipsoid& eb = b_placed[j];
            if (!ellipsoids_may_touch(ea, eb)) continue;
            const Contact contact = ellipsoid_ellipsoid_contact(ea, eb);
            ++touch.exact_tests;
            if (!(contact.depth > 0.0)) continue;
            if (contact.depth > touch.deepest) {
                touch.deepest = contact.depth;
                touch.deepest_contact = contact;
                touch.deepest_a = static_cast<std::uint32_t>(i);
                touch.deepest_b = static_cast<std::uint32_t>(j);
                touch.approach_speed =
                    -glm::dot(relative_velocity(a_before, b_before, contact.point), contact.normal);
            }
            const double budget =
                deep_fraction * std::min(ea.sorted_radii().z, eb.sorted_radii().z);
            stop_if_too_deep(a, b, contact, material, budget);
            press(a, b, contact, material, h);
        }
    }
    return touch;
}

}  // namespace trackphys::detail
