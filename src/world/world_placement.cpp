// add_car's and teleport_car's checks (see World::add_car): a spec whose contacts and wheel
// spins the sub-step integrates stably, and a place where a car may be.

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>
#include <sstream>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "trackphys/error.hpp"
#include "trackphys/geometry/contact.hpp"
#include "trackphys/geometry/ellipsoid_pair.hpp"
#include "trackphys/math/types.hpp"
#include "trackphys/world/world.hpp"
#include "vehicle/rolling_radius.hpp"
#include "world/car_pair_contact.hpp"
#include "world/car_slot.hpp"

namespace trackphys {
namespace {

const char* role_name(EllipsoidRole role) {
    switch (role) {
        case EllipsoidRole::body:
            return "body";
        case EllipsoidRole::front_wheel:
            return "front wheel";
        case EllipsoidRole::rear_wheel:
            return "rear wheel";
    }
    return "ellipsoid";
}

// Euclidean distance from p to the box (0 inside).
double distance_to(const Aabb& box, const glm::dvec3& p) {
    const glm::dvec3 outside = glm::max(glm::max(box.min - p, p - box.max), glm::dvec3(0.0));
    return glm::length(outside);
}

// A lower bound of the car's mass as a contact at body-frame point r feels it: the least
// m_eff = 1 / (1/m + (r x n)^T I^-1 (r x n)) over unit n. (r x n)^T I^-1 (r x n) is at most
// the trace of [r]x^T I^-1 [r]x, sum_i (|r|^2 - r_i^2) / I_i, its largest eigenvalue's at
// most twice (the matrix has rank 2).
double effective_mass_floor(const MassProperties& mass, const glm::dvec3& r) {
    const double r2 = glm::dot(r, r);
    const glm::dvec3& inertia = mass.principal_inertia;
    const double turning =
        (r2 - r.x * r.x) / inertia.x + (r2 - r.y * r.y) / inertia.y + (r2 - r.z * r.z) / inertia.z;
    return 1.0 / (1.0 / mass.mass + turning);
}

// The least of effective_mass_floor over the car's ellipsoids: what another car touching
// any of them may feel.
double car_mass_floor(const CarSpec& spec) {
    double floor = spec.mass.mass;
    for (const CarEllipsoid& e : spec.ellipsoids)
        floor = std::min(floor, effective_mass_floor(spec.mass, e.center));
    return floor;
}

// The tyre load the wheel-spin check takes, in nominal loads. Above
// MagicFormulaCurve::kMaxLoadRatio only the friction coefficient stops falling: the peak
// force, and the slope C with it, grow with the load, which the contact does not bound.
// The default track's banked turns load an outer tyre to 6 at 1000 km/h; a wheel checked
// at 3 passed with a spin that swung 114 rad/s an update at 4.
constexpr double kSpinCheckLoadRatio = 10.0;

// Above low_speed a wheel's spin is explicit against its tyre's force and its slip ratio
// implicit (Vehicle::wheel_force): I w' = -R C k, sigma k' = R w - V - |V| k. Linearised
// about zero slip, with a = h R C / I and b = h R / sigma, the update matrix has determinant
// 1 / d and trace 1 + (1 - a b) / d, d = 1 + h |V| / sigma: stable while
//     a b = h^2 R^2 C / (I sigma) < 4 + 2 h |V| / sigma,
// least at the lowest speed of that update, low_speed. C = B C D is the curve's slope at
// zero slip on a dry road, at kSpinCheckLoadRatio nominal loads; the wheel's inertia
// alone, as an undriven wheel's or one whose clutch is open. Empty when every wheel holds;
// else why not.
std::string wheel_spin_unstable(const CarSpec& spec, double h) {
    const VehicleSpec& v = *spec.vehicle;
    for (std::size_t i = 0; i < spec.ellipsoids.size(); ++i) {
        const CarEllipsoid& e = spec.ellipsoids[i];
        if (e.role == EllipsoidRole::body) continue;
        const bool front = e.role == EllipsoidRole::front_wheel;
        const TyreSpec& tyre = front ? v.front_tyre : v.rear_tyre;
        const MagicFormulaCurve& curve = tyre.longitudinal;
        const double load = kSpinCheckLoadRatio * tyre.nominal_load;
        const double slope = curve.slip_stiffness(curve.peak(load, tyre.nominal_load));
        const double sigma = tyre.longitudinal_relaxation;
        const double r = detail::rolling_radius(e);
        const double growth = h * h * r * r * slope / (v.wheel_inertia * sigma);
        const double limit = 4.0 + 2.0 * h * v.low_speed / sigma;
        if (growth < limit) continue;
        std::ostringstream why;
        why << "World::add_car: CarSpec.vehicle." << (front ? "front_tyre" : "rear_tyre")
            << "'s wheel spin is too stiff for a sub-step of " << h << " s at ellipsoid " << i
            << ": h^2 R^2 C / (wheel_inertia sigma) is " << growth
            << " (slip stiffness C = " << slope << " N at " << load << " N of load, R " << r
            << " m, wheel_inertia " << v.wheel_inertia << " kg m^2, longitudinal_relaxation "
            << sigma << " m), not below the " << limit
            << " (4 + 2 h low_speed / sigma) that the explicit spin update keeps stable";
        return why.str();
    }
    return {};
}

// The suspension's travel follows its massless wheel explicitly: c s' = lift - k s - a (s -
// s_partner), where the lift is the tyre's contact force, k_t (d - s) on flat ground, its
// depth d taken with the wheel placed at the last sub-step's travel. Its modes decay at (k +
// k_t) / c (an axle's wheels together) and (k + k_t + 2 a) / c (against each other, a the
// axle's anti-roll rate); the update is stable while h times the faster one is below 2.
// Beyond it the travel swings between its stops at every sub-step (a damping of 1 N s/m: the
// default car's top speed fell from 139 to 101 km/h). Empty when it holds; else why not.
std::string suspension_unstable(const CarSpec& spec, double h) {
    const Suspension& s = spec.suspension;
    const double springs = s.stiffness + spec.wheel_contact.stiffness;
    const auto check = [&](double anti_roll, const char* bar) -> std::string {
        const double rate = h * (springs + 2.0 * anti_roll) / s.damping;
        if (rate < 2.0) return {};
        std::ostringstream why;
        why << "World::add_car: CarSpec.suspension.damping " << s.damping
            << " N s/m is too low for a sub-step of " << h << " s: h (suspension.stiffness "
            << s.stiffness << " + wheel_contact.stiffness " << spec.wheel_contact.stiffness;
        if (bar) why << " + 2 vehicle." << bar << " " << anti_roll;
        why << ") / damping is " << rate
            << ", not below the 2 that the explicit travel update keeps stable";
        return why.str();
    };
    if (!spec.vehicle) return check(0.0, nullptr);
    std::string why = check(spec.vehicle->front_anti_roll, "front_anti_roll");
    return why.empty() ? check(spec.vehicle->rear_anti_roll, "rear_anti_roll") : why;
}

}  // namespace

void World::check_integrable(const CarSpec& spec) const {
    // Semi-implicit Euler integrates x'' = -(k x + c x') / m stably while h^2 k / m +
    // 2 h c / m <= 4 (the update matrix's determinant 1 - h c / m and trace 2 - h c / m -
    // h^2 k / m). A spring beyond it does not slow the simulation down gracefully: the car
    // gains energy at every sub-step, is reset at every update and sweeps the whole map.
    // car_contact acts between two cars, with their mean material on the pair's mass: it is
    // checked against each car already here (below).
    const double h = settings_.substep_dt();
    for (std::size_t i = 0; i < spec.ellipsoids.size(); ++i) {
        const CarEllipsoid& e = spec.ellipsoids[i];
        const double m = effective_mass_floor(spec.mass, e.center);
        const bool wheel = e.role != EllipsoidRole::body;
        const ContactMaterial& material = wheel ? spec.wheel_contact : spec.body_contact;
        const double growth = h * h * material.stiffness / m + 2.0 * h * material.damping / m;
        if (growth <= 4.0) continue;
        std::ostringstream why;
        why << "World::add_car: CarSpec." << (wheel ? "wheel_contact" : "body_contact")
            << " (stiffness " << material.stiffness << " N/m, damping " << material.damping
            << " N s/m) is too stiff for a sub-step of " << h << " s at ellipsoid " << i << " ("
            << role_name(e.role) << "), where the car's effective mass may be as low as " << m
            << " kg: h^2 k / m + 2 h c / m is " << growth
            << ", above the 4 that the integrator keeps stable";
        throw Error(why.str());
    }
    if (spec.vehicle)
        if (std::string why = wheel_spin_unstable(spec, h); !why.empty()) throw Error(why);
    if (std::string why = suspension_unstable(spec, h); !why.empty()) throw Error(why);
    // Two cars in contact move as one spring-damper on their pair's effective mass, at most
    // the two floors in series (a light car against a heavy one is nearly the light one).
    const double floor = car_mass_floor(spec);
    for (std::size_t other = 0; other < cars_.size(); ++other) {
        const CarSpec& their = cars_[other].car.spec();
        const double m = 1.0 / (1.0 / floor + 1.0 / car_mass_floor(their));
        const ContactMaterial material = detail::mean_material(spec.car_contact, their.car_contact);
        const double growth = h * h * material.stiffness / m + 2.0 * h * material.damping / m;
        if (growth <= 4.0) continue;
        std::ostringstream why;
        why << "World::add_car: CarSpec.car_contact (the mean of this car's and car " << other
            << "'s: stiffness " << material.stiffness << " N/m, damping " << material.damping
            << " N s/m) is too stiff for a sub-step of " << h << " s between the two cars, "
            << "whose pair's effective mass may be as low as " << m
            << " kg: h^2 k / m + 2 h c / m is " << growth
            << ", above the 4 that the integrator keeps stable";
        throw Error(why.str());
    }
}

void World::check_placement(const Car& car, const char* caller, std::size_t index) const {
    const RigidBodyState& state = car.state();
    if (std::string why = impossible_state(state); !why.empty())
        throw Error(std::string(caller) + ": " + why);

    // Far outside the map: farther than max_spawn_distance from every collider's box.
    double nearest = std::numeric_limits<double>::infinity();
    for (std::uint32_t id = 0; id < statics_->size(); ++id) {
        const Aabb& box = statics_->collider(id).bounds();
        if (!box.empty()) nearest = std::min(nearest, distance_to(box, state.position));
    }
    if (std::isfinite(nearest) && nearest > settings_.max_spawn_distance) {
        std::ostringstream why;
        why << caller << ": the car's centre of mass (" << state.position.x << ", "
            << state.position.y << ", " << state.position.z << ") is " << nearest
            << " m from the nearest collider's box, farther than WorldSettings.max_spawn_distance ("
            << settings_.max_spawn_distance << " m): the car is far outside the map";
        throw Error(why.str());
    }

    // Inside geometry: an ellipsoid deeper than half its smallest semi-axis into a triangle
    // (a car resting on a road sinks a few centimetres; this is a car placed through it).
    std::vector<TriangleRef> refs;
    for (std::size_t i = 0; i < car.ellipsoid_count(); ++i) {
        const Ellipsoid ellipsoid = car.world_ellipsoid(i);
        const double limit = 0.5 * ellipsoid.sorted_radii().z;
        refs.clear();
        statics_->query_aabb(ellipsoid.bounds(), refs);
        for (const TriangleRef& ref : refs) {
            const Contact contact = ellipsoid_triangle_contact(
                ellipsoid, statics_->collider(ref.collider).triangle(ref.triangle));
            if (contact.depth > limit) {
                std::ostringstream why;
                why << caller << ": ellipsoid " << i << " ("
                    << role_name(car.spec().ellipsoids[i].role) << ") is " << contact.depth
                    << " m deep in collider " << ref.collider << "'s triangle " << ref.triangle
                    << ", more than half its smallest semi-axis (" << limit
                    << " m): the car starts inside geometry";
                if (car.spec().ellipsoids[i].role != EllipsoidRole::body)
                    why << " (its wheels hang at full droop: place_car_on_surface gives the "
                           "height at which they rest on the road)";
                throw Error(why.str());
            }
        }
    }

    // Inside another car: deeper than cars pressed together by a third sink (0.1 mm), the
    // spring between them would throw them apart (4.4 cm gave 49 km/h, 40 cm 307 km/h).
    constexpr double max_overlap = 1e-3;  // m
    std::vector<Ellipsoid> ours;
    for (std::size_t i = 0; i < car.ellipsoid_count(); ++i) ours.push_back(car.world_ellipsoid(i));
    for (std::size_t other = 0; other < cars_.size(); ++other) {
        if (other == index) continue;
        const Car& them = cars_[other].car;
        const double reach = car.bounding_radius() + them.bounding_radius();
        const glm::dvec3 apart = car.state().position - them.state().position;
        if (glm::dot(apart, apart) > reach * reach) continue;
        for (std::size_t j = 0; j < them.ellipsoid_count(); ++j) {
            const Ellipsoid theirs = them.world_ellipsoid(j);
            for (std::size_t i = 0; i < ours.size(); ++i) {
                if (!ellipsoids_may_touch(ours[i], theirs)) continue;
                const double depth = ellipsoid_ellipsoid_contact(ours[i], theirs).depth;
                if (!(depth > max_overlap)) continue;
                std::ostringstream why;
                why << caller << ": ellipsoid " << i << " ("
                    << role_name(car.spec().ellipsoids[i].role) << ") overlaps car " << other
                    << "'s ellipsoid " << j << " by " << depth << " m, more than the "
                    << max_overlap
                    << " m a resting contact sinks: the spring between them would throw the "
                       "cars apart (place the car clear of the others)";
                throw Error(why.str());
            }
        }
    }
}

}  // namespace trackphys
