#include "trackphys/dynamics/car_spec.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include <glm/geometric.hpp>

#include "trackphys/error.hpp"
#include "trackphys/geometry/ellipsoid.hpp"
#include "trackphys/math/types.hpp"

namespace trackphys {

CarSpec CarSpec::default_car() {
    CarSpec spec;
    spec.mass = MassProperties::solid_box(1200.0, {1.9, 0.9, 4.3});

    // Wheels: the rolling radius is in the car's y-z plane, the width along x.
    const glm::dvec3 wheel_axes(0.15, 0.35, 0.35);
    // A low centre of mass (0.5 m above the ground) and a wide track keep the static
    // stability factor mu h / (track / 2) = 1.2 * 0.5 / 0.9 = 0.67 below 1: a car sliding
    // sideways with full grip slides instead of tripping over its outer wheels.
    const double wheel_y = -0.15;
    for (double side : {1.0, -1.0}) {
        spec.ellipsoids.push_back(
            {{0.9 * side, wheel_y, 1.45}, wheel_axes, {1, 0, 0, 0}, EllipsoidRole::front_wheel});
        spec.ellipsoids.push_back(
            {{0.9 * side, wheel_y, -1.35}, wheel_axes, {1, 0, 0, 0}, EllipsoidRole::rear_wheel});
    }
    // Body: nose, cabin, tail and a wide floor pan, all clear of the road at rest.
    spec.ellipsoids.push_back(
        {{0.0, 0.05, 1.70}, {0.80, 0.25, 0.60}, {1, 0, 0, 0}, EllipsoidRole::body});
    spec.ellipsoids.push_back(
        {{0.0, 0.35, 0.00}, {0.75, 0.40, 1.20}, {1, 0, 0, 0}, EllipsoidRole::body});
    spec.ellipsoids.push_back(
        {{0.0, 0.10, -1.70}, {0.85, 0.30, 0.55}, {1, 0, 0, 0}, EllipsoidRole::body});
    spec.ellipsoids.push_back(
        {{0.0, -0.05, 0.00}, {0.95, 0.20, 1.90}, {1, 0, 0, 0}, EllipsoidRole::body});

    // Per wheel load m g / 4 = 2943 N; k = 4e5 N/m (a racing tyre) sags 0.74 cm; critical
    // damping for a quarter car is 2 sqrt(k m / 4) = 2.2e4 N s/m. A 2e5 N/m tyre sank 7 cm
    // under the 3-4 g of the banked turns, past the r_min^2 / r_max = 6.4 cm below which the
    // exact contact certifies a wheel's face contact at once: the exact phase took 3x longer
    // in those updates.
    spec.wheel_contact = {4.0e5, 2.1e4, 1.2, 0.05};
    // The body rarely touches; stiffer so a scrape does not sink it.
    spec.body_contact = {8.0e5, 3.0e4, 0.6, 0.05};
    return spec;
}

double CarSpec::lowest_point_depth() const {
    double lowest = 0.0;
    for (const CarEllipsoid& e : ellipsoids)
        lowest = std::min(lowest, Ellipsoid(e.center, e.orientation, e.semi_axes).bounds().min.y);
    return -lowest;
}

namespace {

void check_positive(std::ostringstream& why, const char* field, double value) {
    if (why.tellp() == 0 && !(std::isfinite(value) && value > 0.0))
        why << "CarSpec." << field << " must be finite and > 0, got " << exact_text(value);
}

void check_non_negative(std::ostringstream& why, const char* field, double value) {
    if (why.tellp() == 0 && !(std::isfinite(value) && value >= 0.0))
        why << "CarSpec." << field << " must be finite and >= 0, got " << exact_text(value);
}

void check_material(std::ostringstream& why, const char* name, const ContactMaterial& m) {
    const std::string prefix = std::string(name) + ".";
    check_positive(why, (prefix + "stiffness").c_str(), m.stiffness);
    check_non_negative(why, (prefix + "damping").c_str(), m.damping);
    check_non_negative(why, (prefix + "friction").c_str(), m.friction);
    check_positive(why, (prefix + "slip_speed").c_str(), m.slip_speed);
}

}  // namespace

std::string CarSpec::validate() const {
    std::ostringstream why;
    check_positive(why, "mass.mass", mass.mass);
    check_positive(why, "mass.principal_inertia.x", mass.principal_inertia.x);
    check_positive(why, "mass.principal_inertia.y", mass.principal_inertia.y);
    check_positive(why, "mass.principal_inertia.z", mass.principal_inertia.z);
    // Every body has I_x + I_y >= I_z (the integrals of x^2 + z^2 and y^2 + z^2 hold the one
    // of x^2 + y^2), and so on round; moments that break it spin the car up without bound.
    // The margin lets a flat body's equality through its rounding.
    for (int k = 0; k < 3 && why.tellp() == 0; ++k) {
        const glm::dvec3& i = mass.principal_inertia;
        const double others = i[(k + 1) % 3] + i[(k + 2) % 3];
        if (!(i[k] <= others * (1.0 + 0x1p-40)))
            why << "CarSpec.mass.principal_inertia."
                << "xyz"[k] << " is " << i[k] << ", more than the other two moments together ("
                << others << "): no body has such moments";
    }
    if (why.tellp() == 0 && (ellipsoids.empty() || ellipsoids.size() > max_ellipsoids))
        why << "CarSpec.ellipsoids must hold 1 to " << max_ellipsoids << " ellipsoids, got "
            << ellipsoids.size();
    for (std::size_t i = 0; i < ellipsoids.size() && why.tellp() == 0; ++i) {
        const CarEllipsoid& e = ellipsoids[i];
        const std::string prefix = "ellipsoids[" + std::to_string(i) + "].";
        static constexpr const char* axis[3] = {"x", "y", "z"};
        if (!is_finite(e.center)) why << "CarSpec." << prefix << "center is not finite";
        // Its length overflows beyond 1e154 m: each coordinate is bounded first.
        const glm::dvec3 c = e.center;
        if (why.tellp() == 0 &&
            !(std::max({std::abs(c.x), std::abs(c.y), std::abs(c.z)}) <= max_extent &&
              glm::length(c) <= max_extent))
            why << "CarSpec." << prefix << "center (" << exact_text(c.x) << ", " << exact_text(c.y)
                << ", " << exact_text(c.z) << ") is beyond the " << max_extent
                << " m from the centre of mass that a car may reach";
        for (int k = 0; k < 3; ++k) {
            const std::string name = prefix + "semi_axes." + axis[k];
            check_positive(why, name.c_str(), e.semi_axes[k]);
            if (why.tellp() == 0 && !(e.semi_axes[k] <= max_extent))
                why << "CarSpec." << name << " must be at most " << max_extent << " m, got "
                    << exact_text(e.semi_axes[k]);
        }
        if (why.tellp() == 0 && !(is_finite(e.orientation) && glm::length(e.orientation) > 0.5))
            why << "CarSpec." << prefix << "orientation must be a finite unit quaternion";
    }
    check_material(why, "body_contact", body_contact);
    check_material(why, "wheel_contact", wheel_contact);
    check_material(why, "car_contact", car_contact);
    check_positive(why, "rear_grip_factor", rear_grip_factor);
    check_positive(why, "suspension.stiffness", suspension.stiffness);
    check_positive(why, "suspension.damping", suspension.damping);
    check_non_negative(why, "suspension.travel", suspension.travel);
    check_non_negative(why, "max_drive_force", max_drive_force);
    check_non_negative(why, "max_drive_power", max_drive_power);
    check_non_negative(why, "max_reverse_speed", max_reverse_speed);
    if (why.tellp() == 0 && !(front_drive_share >= 0.0 && front_drive_share <= 1.0))
        why << "CarSpec.front_drive_share must be in [0, 1], got " << exact_text(front_drive_share);
    if (why.tellp() == 0 && !(front_brake_share >= 0.0 && front_brake_share <= 1.0))
        why << "CarSpec.front_brake_share must be in [0, 1], got " << exact_text(front_brake_share);
    if (why.tellp() == 0 && !(traction_limit >= 0.0 && traction_limit <= 1.0))
        why << "CarSpec.traction_limit must be in [0, 1], got " << exact_text(traction_limit);
    check_non_negative(why, "max_brake_force", max_brake_force);
    check_non_negative(why, "max_steer_angle", max_steer_angle);
    if (why.tellp() == 0 && !(max_steer_angle < 1.5))
        why << "CarSpec.max_steer_angle must be below 1.5 rad, got " << exact_text(max_steer_angle);
    if (why.tellp() == 0 && !(deep_contact_fraction > 0.0 && deep_contact_fraction <= 1.0))
        why << "CarSpec.deep_contact_fraction must be in (0, 1], got "
            << exact_text(deep_contact_fraction);
    check_non_negative(why, "drag_area", drag_area);
    check_non_negative(why, "downforce_area", downforce_area);
    check_non_negative(why, "air_density", air_density);
    if (why.tellp() == 0 && vehicle) return vehicle->validate();
    return why.str();
}

}  // namespace trackphys
