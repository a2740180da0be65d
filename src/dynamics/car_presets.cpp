// CarSpec::preset: the arcade car and the two vehicle-model cars (docs/vehicle.md#presets).

#include <array>
#include <string>

#include "trackphys/dynamics/car_spec.hpp"
#include "trackphys/error.hpp"

namespace trackphys {
namespace {

constexpr std::array<std::string_view, 3> kPresetNames = {"arcade", "gt", "formula"};

// Vertical damping of the slick's carcass (N s/m), half the arcade car's: the stiffly
// damped tyre bounced off the kinks between the road's facets at 200 km/h, and a tyre in
// the air has no grip (the arcade car's grip does not care).
constexpr double kTyreDamping = 1.0e4;

// Moves the centre of mass down by drop metres (every ellipsoid up in the body frame).
// The arcade car's 0.5 m keeps its static stability factor mu h / (track / 2) at 0.67 for
// mu 1.2; slicks near 1.7 would put it at 1, on the edge of rolling over in every fast
// turn (the inside wheels lifted at 245 km/h).
void lower_centre_of_mass(CarSpec& spec, double drop) {
    for (CarEllipsoid& e : spec.ellipsoids) e.center.y += drop;
}

// A rear tyre wider than the front grips 10% more: with equal tyres a rear-driven car
// is on the edge of power oversteer at every exit; more rear grip makes it understeer, as
// racing cars are set up to.
TyreSpec wider(TyreSpec tyre) {
    tyre.longitudinal.friction *= 1.1;
    tyre.lateral.friction *= 1.1;
    return tyre;
}

// A GT3-class coupe: 1300 kg, 480 N m at 5000 rpm (338 kW at most, near 8500), six gears, slicks,
// rear drive through a limited-slip differential, moderate downforce.
CarSpec gt_car() {
    CarSpec spec = CarSpec::default_car();
    spec.mass = MassProperties::solid_box(1300.0, {1.9, 0.9, 4.3});
    lower_centre_of_mass(spec, 0.15);  // 0.35 m above the road
    spec.front_drive_share = 0.0;
    spec.front_brake_share = 0.6;
    spec.drag_area = 0.8;
    spec.downforce_area = 1.5;
    spec.wheel_contact.damping = kTyreDamping;
    VehicleSpec v;
    v.model = "gt";
    v.front_tyre = TyreSpec::slick();
    v.rear_tyre = wider(TyreSpec::slick());
    v.wheel_inertia = 1.2;
    v.engine.torque_curve = {{1000, 300}, {3000, 420}, {5000, 480}, {6500, 470}, {8500, 380}};
    v.engine.idle_rpm = 1000.0;
    v.engine.redline_rpm = 8500.0;
    v.engine.inertia = 0.15;
    v.engine.friction_torque = 60.0;
    v.gearbox.ratios = {3.2, 2.3, 1.8, 1.45, 1.2, 1.0};
    v.gearbox.reverse_ratio = 3.5;
    v.gearbox.final_drive = 3.6;
    v.gearbox.shift_up_rpm = 8000.0;
    v.gearbox.shift_down_rpm = 4000.0;
    v.gearbox.shift_time = 0.08;
    v.gearbox.clutch_engage_time = 0.05;
    v.gearbox.launch_rpm = 4000.0;
    v.rear_differential = {DifferentialKind::limited_slip, 100.0, 0.3};
    v.max_brake_torque = 10000.0;
    v.front_anti_roll = 3.0e4;
    v.rear_anti_roll = 2.0e4;
    v.rolling_resistance = 0.012;
    spec.vehicle = v;
    return spec;
}

// A single-seater: 750 kg, 420 N m to 13500 rpm (about 500 kW), eight gears, slicks, rear
// drive through a limited-slip differential, downforce above its weight at 250 km/h.
CarSpec formula_car() {
    CarSpec spec = CarSpec::default_car();
    spec.mass = MassProperties::solid_box(750.0, {1.8, 0.8, 4.5});
    lower_centre_of_mass(spec, 0.2);  // 0.3 m above the road
    spec.front_drive_share = 0.0;
    spec.front_brake_share = 0.6;
    spec.drag_area = 1.0;
    spec.downforce_area = 3.0;
    spec.wheel_contact.damping = kTyreDamping;
    VehicleSpec v;
    v.model = "formula";
    v.front_tyre = TyreSpec::slick();
    v.rear_tyre = wider(TyreSpec::slick());
    v.wheel_inertia = 0.8;
    v.engine.torque_curve = {{1000, 200}, {6000, 380}, {10000, 420}, {12000, 400}, {13500, 370}};
    v.engine.idle_rpm = 4000.0;
    v.engine.redline_rpm = 13500.0;
    v.engine.inertia = 0.06;
    v.engine.friction_torque = 80.0;
    v.gearbox.ratios = {2.9, 2.3, 1.9, 1.6, 1.42, 1.28, 1.17, 1.08};
    v.gearbox.reverse_ratio = 3.2;
    v.gearbox.final_drive = 4.0;
    v.gearbox.shift_up_rpm = 12500.0;
    v.gearbox.shift_down_rpm = 8000.0;
    v.gearbox.shift_time = 0.03;
    v.gearbox.clutch_engage_time = 0.02;
    v.gearbox.launch_rpm = 7000.0;
    v.rear_differential = {DifferentialKind::limited_slip, 50.0, 0.3};
    v.max_brake_torque = 9000.0;
    v.front_anti_roll = 2.0e4;
    v.rear_anti_roll = 1.5e4;
    v.rolling_resistance = 0.010;
    spec.vehicle = v;
    return spec;
}

}  // namespace

std::span<const std::string_view> CarSpec::preset_names() { return kPresetNames; }

CarSpec CarSpec::preset(std::string_view name) {
    if (name == "arcade") return default_car();
    if (name == "gt") return gt_car();
    if (name == "formula") return formula_car();
    throw Error("unknown car preset " + quoted_text(name) + " (expected arcade, gt or formula)");
}

}  // namespace trackphys
