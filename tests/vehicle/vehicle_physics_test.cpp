// The vehicle model against references computed here, independently of it: 0-100 km/h
// from the torque curve, gears and the tyre's slip limit; 100-0 from the tyres' peak; a
// limited-slip differential against an open one with a wheel on ice; a parked car that
// stays put; a launch after landing, a teleport, a brake and a reset that leave the wheels
// as they should; snapshots that carry the wheels and the gearbox; a coast slowed by drag,
// rolling resistance and engine braking; a sideways slide gripping as the curve says at
// low speed; and reverse, for the arcade car too.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <optional>
#include <string>
#include <string_view>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

#include "support/error_message.hpp"
#include "trackphys/error.hpp"
#include "trackphys/io/snapshot_file.hpp"
#include "trackphys/world/spawn.hpp"
#include "trackphys/world/world.hpp"
#include "vehicle/vehicle_access.hpp"
#include "world/world_scenes.hpp"

namespace trackphys {
namespace {

constexpr double g = 9.81;

// A world with the car placed on the mesh at (x, z), facing +Z.
World world_with(const TriangleMesh& mesh, const CarSpec& spec, double x = 0.0, double z = 0.0) {
    World world(test::static_world_of(mesh));
    world.add_car(spec, place_car_on_surface(world.statics(), spec, {x, 20.0, z},
                                             glm::dquat(1.0, 0.0, 0.0, 0.0)));
    return world;
}

double forward_speed(const Car& car) {
    return glm::dot(car.state().linear_velocity,
                    car.state().orientation * glm::dvec3(0.0, 0.0, 1.0));
}

void drive(World& world, const CarInputs& inputs, double seconds) {
    for (int i = 0; i < static_cast<int>(std::lround(seconds / world.settings().dt_update)); ++i) {
        world.car(0).set_inputs(inputs);
        world.update();
    }
}

// A Magic Formula curve's peak force D = mu (1 + slope dfz) F_z at load F_z (N), with
// dfz = F_z / F_z0 - 1 held at 2 beyond three times the nominal load (docs/vehicle.md),
// from the tyre's coefficients.
double peak_force(const TyreSpec& tyre, const MagicFormulaCurve& curve, double load) {
    const double dfz = std::min(load / tyre.nominal_load - 1.0, 2.0);
    return curve.friction * (1.0 + curve.friction_load_slope * dfz) * load;
}

// What the reference needs of the car: its geometry and what its spec says.
struct PointCar {
    explicit PointCar(const CarSpec& car, double cg_height)
        : spec(car), v(*car.vehicle), height(cg_height) {
        double front = 0.0, rear = 0.0;
        for (const CarEllipsoid& e : car.ellipsoids) {
            if (e.role == EllipsoidRole::front_wheel) front = e.center.z, radius = e.semi_axes.y;
            if (e.role == EllipsoidRole::rear_wheel) rear = e.center.z;
        }
        wheelbase = front - rear;
        front_static = -rear / wheelbase;  // the share of the weight on the front axle
    }
    double aero(double area, double speed) const {
        return 0.5 * spec.air_density * area * speed * speed;
    }
    // Air drag and rolling resistance, c_rr of the weight and the downforce (N).
    double resistance(double speed) const {
        return aero(spec.drag_area, speed) +
               v.rolling_resistance * (spec.mass.mass * g + aero(spec.downforce_area, speed));
    }
    // The axle loads (N) at speed and forward acceleration a (m/s^2): weight and downforce
    // shared as the centre of mass sits, plus the load transfer m a h / L.
    double front_load(double speed, double a) const {
        return (spec.mass.mass * g + aero(spec.downforce_area, speed)) * front_static -
               spec.mass.mass * a * height / wheelbase;
    }
    double rear_load(double speed, double a) const {
        return spec.mass.mass * g + aero(spec.downforce_area, speed) - front_load(speed, a);
    }
    // An axle's peak longitudinal force: two tyres at half its load each.
    static double axle_peak(const TyreSpec& tyre, double load) {
        return 2.0 * peak_force(tyre, tyre.longitudinal, 0.5 * load);
    }
    double full_torque(double rpm) const {
        const auto& curve = v.engine.torque_curve;
        if (rpm <= curve.front().rpm) return curve.front().torque;
        for (std::size_t k = 1; k < curve.size(); ++k)
            if (rpm < curve[k].rpm)
                return curve[k - 1].torque + (rpm - curve[k - 1].rpm) /
                                                 (curve[k].rpm - curve[k - 1].rpm) *
                                                 (curve[k].torque - curve[k - 1].torque);
        return curve.back().torque;
    }

    const CarSpec& spec;
    const VehicleSpec& v;
    double height;
    double radius = 0.0;
    double wheelbase = 0.0;
    double front_static = 0.5;
};

// 0 to 100 km/h of a rear-driven car by explicit integration in 0.1 ms steps: the engine's
// force through the gear (at launch_rpm while the clutch slips) less drag and rolling
// resistance, on the mass plus the wheels' and the engine's rotating inertia; or, when the
// rear tyres' peak under the load transfer limits, that peak less the same on the mass and
// the undriven wheels only (the
// engine's surplus torque then turns the engine and the driven wheels, not the car). No
// drive while a shift lasts, then the clutch closes linearly.
double reference_zero_to_100(const PointCar& car) {
    const double m = car.spec.mass.mass;
    const double r = car.radius;
    const GearboxSpec& box = car.v.gearbox;
    double speed = 0.0, a = 0.0, t = 0.0, shift_left = 0.0, clutch = 1.0;
    std::size_t gear = 0;
    const double dt = 1e-4;
    while (speed < 100.0 / 3.6) {
        const double ratio = box.ratios[gear] * box.final_drive;
        const double rpm = speed / r * ratio * 60.0 / (2.0 * std::numbers::pi);
        const bool locked = rpm >= box.launch_rpm;
        const double engine = clutch * car.full_torque(locked ? rpm : box.launch_rpm) * ratio / r;
        const double grip = PointCar::axle_peak(car.v.rear_tyre, car.rear_load(speed, a));
        const double rotating =
            4.0 * car.v.wheel_inertia / (r * r) +
            (locked ? clutch * car.v.engine.inertia * ratio * ratio / (r * r) : 0.0);
        const double undriven = 2.0 * car.v.wheel_inertia / (r * r);
        const double drag = car.resistance(speed);
        a = std::min((engine - drag) / (m + rotating), (grip - drag) / (m + undriven));
        speed += a * dt;
        t += dt;
        if (shift_left > 0.0) {
            shift_left -= dt;
            clutch = 0.0;
        } else {
            clutch = std::min(1.0, clutch + dt / box.clutch_engage_time);
            if (clutch == 1.0 && rpm > box.shift_up_rpm && gear + 1 < box.ratios.size()) {
                ++gear;
                shift_left = box.shift_time;
                clutch = 0.0;
            }
        }
    }
    return t;
}

// 100 km/h to 1 m/s with every tyre at its longitudinal peak (anti-lock) under the load
// transfer, plus drag and rolling resistance.
double reference_braking(const PointCar& car) {
    const double m = car.spec.mass.mass;
    double speed = 100.0 / 3.6, decel = 0.0, t = 0.0;
    const double dt = 1e-4;
    while (speed > 1.0) {
        const double grip = PointCar::axle_peak(car.v.front_tyre, car.front_load(speed, -decel)) +
                            PointCar::axle_peak(car.v.rear_tyre, car.rear_load(speed, -decel));
        decel = (grip + car.resistance(speed)) / m;
        speed -= decel * dt;
        t += dt;
    }
    return t;
}

// The engine's full-throttle torque interpolates its curve linearly, held at the ends: the
// same bits as a scan of the points (the reference below) at each point, between points and
// beyond both ends, for both presets' curves and one of the most points allowed.
TEST(VehiclePhysics, FullThrottleTorqueFollowsTheCurve) {
    CarSpec dense = CarSpec::preset("gt");
    auto& curve = dense.vehicle->engine.torque_curve;
    curve.clear();
    for (std::size_t k = 0; k < EngineSpec::max_torque_points; ++k)
        curve.push_back({500.0 + 2.0 * double(k), 300.0 + 100.0 * std::sin(0.01 * double(k))});
    dense.vehicle->engine.redline_rpm = 9000.0;
    for (const CarSpec& spec : {CarSpec::preset("gt"), CarSpec::preset("formula"), dense}) {
        const Vehicle vehicle(spec);
        const PointCar car(spec, 0.0);  // its full_torque, a scan of the points
        const auto& points = spec.vehicle->engine.torque_curve;
        std::vector<double> rpms = {0.0, points.front().rpm - 1.0, points.back().rpm + 1.0};
        for (std::size_t k = 0; k < points.size(); ++k) {
            rpms.push_back(points[k].rpm);
            if (k + 1 < points.size()) rpms.push_back(0.5 * (points[k].rpm + points[k + 1].rpm));
        }
        for (const double rpm : rpms) {
            if (rpm > spec.vehicle->engine.redline_rpm) continue;  // the limiter's
            EXPECT_EQ(detail::VehicleAccess::engine_torque(vehicle, rpm, 1.0), car.full_torque(rpm))
                << rpm << " rpm";
        }
    }
}

TEST(VehiclePhysics, AcceleratesAndBrakesAsTheReferencesSay) {
    const CarSpec spec = CarSpec::preset("gt");
    World world = world_with(test::straight_road(400.0, 20.0, 10.0), spec, 0.0, 10.0);
    drive(world, {}, 1.0);  // settle onto the tyres
    ASSERT_LT(world.car(0).speed(), 1e-3);
    const PointCar car(spec, world.car(0).state().position.y);

    double t = 0.0;
    while (forward_speed(world.car(0)) < 100.0 / 3.6 && t < 20.0) {
        drive(world, {1.0, 0.0, 0.0}, world.settings().dt_update);
        t += world.settings().dt_update;
    }
    const double expected = reference_zero_to_100(car);
    RecordProperty("zero_to_100_s", std::to_string(t));
    RecordProperty("zero_to_100_reference_s", std::to_string(expected));
    EXPECT_NEAR(t, expected, 0.03 * expected) << "0-100 km/h in " << t << " s";
    EXPECT_EQ(world.car_resets(0), 0u);

    while (forward_speed(world.car(0)) < 105.0 / 3.6)
        drive(world, {1.0, 0.0, 0.0}, world.settings().dt_update);
    while (forward_speed(world.car(0)) > 100.0 / 3.6)
        drive(world, {0.0, 1.0, 0.0}, world.settings().dt_update);
    t = 0.0;
    while (forward_speed(world.car(0)) > 1.0 && t < 20.0) {
        drive(world, {0.0, 1.0, 0.0}, world.settings().dt_update);
        t += world.settings().dt_update;
    }
    const double braking = reference_braking(car);
    RecordProperty("braking_s", std::to_string(t));
    RecordProperty("braking_reference_s", std::to_string(braking));
    EXPECT_NEAR(t, braking, 0.03 * braking) << "100 km/h to 1 m/s in " << t << " s";
}

// Seconds of full throttle until the car's forward speed reaches 5 km/h.
double seconds_to_walking_pace(World& world) {
    double t = 0.0;
    while (forward_speed(world.car(0)) < 5.0 / 3.6 && t < 5.0) {
        drive(world, {1.0, 0.0, 0.0}, world.settings().dt_update);
        t += world.settings().dt_update;
    }
    return t;
}

// Full throttle from the spawn, 1 mm above the road, and a landing with the driven wheels
// spinning: once down, the car must launch about as a car settled on its tyres does, not
// sit at walking pace while traction control cuts the drive and a slip ratio built in the
// air relaxes at |V_x| / sigma (0.88 s to 5 km/h for the gt, 0.78 s for the formula).
TEST(VehiclePhysics, ThrottleHeldFromTheSpawnOrALandingLaunchesAsFromRest) {
    for (const char* preset : {"gt", "formula"}) {
        SCOPED_TRACE(preset);
        const CarSpec spec = CarSpec::preset(preset);
        World settled = world_with(test::flat_grid(400.0, 20), spec);
        drive(settled, {}, 1.0);
        const double from_rest = seconds_to_walking_pace(settled);

        World spawned = world_with(test::flat_grid(400.0, 20), spec);
        drive(spawned, {1.0, 0.0, 0.0}, spawned.settings().dt_update);
        for (const WheelTelemetry& wheel : spawned.car(0).vehicle()->telemetry())
            ASSERT_EQ(wheel.load, 0.0) << "the car did not start in the air";
        const double from_spawn = seconds_to_walking_pace(spawned);

        World landing = world_with(test::flat_grid(400.0, 20), spec);
        VehicleState spinning = landing.car(0).vehicle()->state();
        for (WheelState& wheel : spinning.wheels) wheel.spin = 30.0;
        landing.car(0).set_vehicle_state(spinning);
        const double from_landing = seconds_to_walking_pace(landing);

        RecordProperty(std::string(preset) + "_to_5_kmh_from_rest_s", std::to_string(from_rest));
        RecordProperty(std::string(preset) + "_to_5_kmh_from_spawn_s", std::to_string(from_spawn));
        RecordProperty(std::string(preset) + "_to_5_kmh_landing_spinning_s",
                       std::to_string(from_landing));
        EXPECT_LT(from_spawn, from_rest + 0.2)
            << "5 km/h after " << from_spawn << " s from the spawn, " << from_rest
            << " s from rest";
        EXPECT_LT(from_landing, from_rest + 0.2)
            << "5 km/h after " << from_landing << " s landing, " << from_rest << " s from rest";
        EXPECT_EQ(spawned.car_resets(0) + landing.car_resets(0), 0u);
    }
}

// A teleport (Car::set_state, a race's rescue) of a gt stopped in first gear to 60 m/s:
// it must arrive rolling, its wheels spun to the road's speed without slip, in a gear
// for that speed, its suspension at full droop as placing assumes, and drive on, not
// land on stopped wheels that skid while the engine, dragged over its redline in first
// gear, has its fuel cut.
TEST(VehiclePhysics, ATeleportedCarArrivesRollingInAGearForItsSpeed) {
    const CarSpec spec = CarSpec::preset("gt");
    World world = world_with(test::flat_grid(2000.0, 20), spec, 0.0, -900.0);
    drive(world, {}, 1.0);
    Car& car = world.car(0);
    ASSERT_EQ(car.vehicle()->state().gear, 1);
    ASSERT_GT(car.suspension(0) + car.suspension(1), 0.0);

    // Placed 800 m on, as a rescue places a car: on its wheels at full droop.
    const double speed = 60.0;
    RigidBodyState moved =
        place_car_on_surface(world.statics(), spec, {0.0, 20.0, -100.0}, car.state().orientation);
    moved.linear_velocity = moved.orientation * glm::dvec3(0.0, 0.0, speed);
    car.set_state(moved);
    const VehicleState& rolling = car.vehicle()->state();
    const GearboxSpec& box = spec.vehicle->gearbox;
    const double radius = PointCar(spec, 0.0).radius;
    for (const WheelState& wheel : rolling.wheels) {
        EXPECT_DOUBLE_EQ(wheel.spin, speed / radius);
        EXPECT_EQ(wheel.slip_ratio, 0.0);
        EXPECT_EQ(wheel.lateral_slip, 0.0);
    }
    const auto rpm_in = [&](int gear) {
        return speed / radius * box.ratios[static_cast<std::size_t>(gear - 1)] * box.final_drive *
               60.0 / (2.0 * std::numbers::pi);
    };
    EXPECT_LE(rpm_in(rolling.gear), box.shift_up_rpm);
    EXPECT_GT(rpm_in(rolling.gear - 1), box.shift_up_rpm) << "gear " << rolling.gear;
    EXPECT_EQ(rolling.clutch, 1.0);
    for (double travel : car.suspension()) EXPECT_EQ(travel, 0.0);

    double slowest = speed, fastest_engine = 0.0;
    for (int i = 0; i < 100; ++i) {
        drive(world, {1.0, 0.0, 0.0}, world.settings().dt_update);
        slowest = std::min(slowest, forward_speed(car));
        fastest_engine = std::max(fastest_engine, car.vehicle()->engine_rpm());
    }
    EXPECT_LE(fastest_engine, spec.vehicle->engine.redline_rpm);
    EXPECT_GT(slowest, speed - 0.5) << "slowed to " << slowest << " m/s";
    EXPECT_GT(forward_speed(car), speed);
    EXPECT_EQ(world.car_resets(0), 0u);
}

// A reversing car teleported (a rescue of a car backing out) keeps reversing: at or below
// -reverse_engage_speed it arrives in reverse, where the shifter would hold it; above, in
// a forward gear.
TEST(VehiclePhysics, ATeleportBackwardsArrivesInReverse) {
    const Vehicle gt(CarSpec::preset("gt"));
    const double engage = CarSpec::reverse_engage_speed;
    EXPECT_EQ(gt.rolling_at(-5.0).gear, VehicleState::reverse_gear);
    EXPECT_EQ(gt.rolling_at(-engage).gear, VehicleState::reverse_gear);
    EXPECT_EQ(gt.rolling_at(-0.5 * engage).gear, 1);
    for (const WheelState& wheel : gt.rolling_at(-5.0).wheels) EXPECT_LT(wheel.spin, 0.0);
}

// A car sliding at `speed` along its heading (< 0 backwards) on the flat, its wheels rolling
// with it in `gear`: a spun car still in a forward gear, or one braking on locked wheels.
World sliding(const CarSpec& spec, double speed, int gear) {
    World world = world_with(test::flat_grid(2000.0, 20), spec, 0.0, -500.0);
    drive(world, {}, 1.0);
    Car& car = world.car(0);
    RigidBodyState state = car.state();
    state.linear_velocity = state.orientation * glm::dvec3(0.0, 0.0, speed);
    car.set_state(state);
    VehicleState rolling = car.vehicle()->rolling_at(speed);
    rolling.gear = gear;
    car.set_vehicle_state(rolling);
    return world;
}

// A braked wheel turns slower than the road moves whichever way the car goes: anti-lock
// must read the slip against the car's motion, not against the gear's direction. A gt spun
// round, sliding backwards at 15 m/s in first gear under full brake, keeps its wheels
// turning (near the peak slip), as it does sliding forwards.
TEST(VehiclePhysics, AntiLockHoldsTheWheelsOfACarSlidingBackwardsInAForwardGear) {
    for (const double speed : {15.0, -15.0}) {
        SCOPED_TRACE(speed);
        const CarSpec spec = CarSpec::preset("gt");
        const double radius = PointCar(spec, 0.0).radius;
        World world = sliding(spec, speed, 1);
        const Car& car = world.car(0);
        double least_rolling_share = 1.0;
        for (int i = 0; i < 30; ++i) {
            drive(world, {0.0, 1.0, 0.0}, world.settings().dt_update);
            for (const WheelState& wheel : car.vehicle()->state().wheels)
                least_rolling_share =
                    std::min(least_rolling_share, wheel.spin * radius / forward_speed(car));
        }
        EXPECT_GT(std::abs(forward_speed(car)), 10.0);
        EXPECT_GT(least_rolling_share, 0.5) << "a wheel locked";
    }
}

// Reverse engages only once the car is nearly stopped, wheels and body: a gt without
// anti-lock, braked to locked wheels at 30 m/s with the throttle at -1, must not engage
// reverse while it still slides forwards (its wheels' rolling speed alone reads 0).
TEST(VehiclePhysics, LockedWheelsOnACarSlidingForwardsDoNotEngageReverse) {
    CarSpec spec = CarSpec::preset("gt");
    spec.vehicle->anti_lock = false;
    World world = sliding(spec, 30.0, 3);
    const Car& car = world.car(0);
    while (forward_speed(car) > 2.0) {
        drive(world, {-1.0, 1.0, 0.0}, world.settings().dt_update);
        ASSERT_NE(car.vehicle()->state().gear, VehicleState::reverse_gear)
            << "at " << forward_speed(car) << " m/s";
    }
}

// Full brake from 20 m/s to a stop, through the explicit spin update above low_speed and
// the damped one below it: the brake takes each wheel's spin towards zero and holds it
// there, never past it (a brake that reversed a wheel would push the car backwards).
TEST(VehiclePhysics, ABrakeStopsAWheelAndNeverReversesIt) {
    for (const bool anti_lock : {true, false}) {
        SCOPED_TRACE(anti_lock ? "anti-lock" : "no anti-lock");
        CarSpec spec = CarSpec::preset("gt");
        spec.vehicle->anti_lock = anti_lock;
        World world = world_with(test::flat_grid(2000.0, 20), spec, 0.0, -900.0);
        drive(world, {}, 1.0);
        while (forward_speed(world.car(0)) < 20.0)
            drive(world, {1.0, 0.0, 0.0}, world.settings().dt_update);
        double slowest_spin = 0.0;
        for (int i = 0; i < 600; ++i) {
            drive(world, {0.0, 1.0, 0.0}, world.settings().dt_update);
            for (const WheelState& wheel : world.car(0).vehicle()->state().wheels)
                slowest_spin = std::min(slowest_spin, wheel.spin);
        }
        EXPECT_EQ(slowest_spin, 0.0);
        EXPECT_LT(world.car(0).speed(), 1e-3);
        for (const WheelState& wheel : world.car(0).vehicle()->state().wheels)
            EXPECT_EQ(wheel.spin, 0.0);
    }
}

// The World's reset policy puts a gt that broke WorldSettings::max_car_speed (30 m/s here)
// in second gear back where its update began, at rest: its vehicle too, wheels still,
// first gear, clutch closed (Vehicle::at_rest), and it drives off again from there.
TEST(VehiclePhysics, AResetCarStartsAgainAtRestInFirstGear) {
    const CarSpec spec = CarSpec::preset("gt");
    WorldSettings settings;
    settings.max_car_speed = 30.0;
    World world(test::static_world_of(test::flat_grid(2000.0, 20)), settings);
    const RigidBodyState start = place_car_on_surface(world.statics(), spec, {0.0, 20.0, -900.0},
                                                      glm::dquat(1.0, 0.0, 0.0, 0.0));
    world.add_car(spec, start);
    int updates = 0, gear_before = 1;
    while (world.car_resets(0) == 0 && updates++ < 2000) {
        gear_before = world.car(0).vehicle()->state().gear;
        drive(world, {1.0, 0.0, 0.0}, world.settings().dt_update);
    }
    ASSERT_EQ(world.car_resets(0), 1u);
    EXPECT_GT(gear_before, 1);
    const Vehicle& vehicle = *world.car(0).vehicle();
    EXPECT_EQ(vehicle.state(), vehicle.at_rest());
    EXPECT_EQ(vehicle.state().gear, 1);
    EXPECT_EQ(world.car(0).speed(), 0.0);
    drive(world, {1.0, 0.0, 0.0}, 1.0);
    EXPECT_GT(forward_speed(world.car(0)), 5.0);
    EXPECT_EQ(world.car_resets(0), 1u);
}

// Road grip is the environment's, set by the game wheel by wheel: a slot past the wheels or
// a grip that is not finite and above 0 is refused, naming the slot (a negative grip would
// push the tyre along its slip, zero would leave its force 0 / 0).
TEST(VehiclePhysics, RoadGripMustBeFiniteAndAboveZeroForAWheelThatExists) {
    Vehicle vehicle(CarSpec::preset("gt"));
    const std::size_t wheels = vehicle.state().wheels.size();
    EXPECT_NO_THROW(vehicle.set_road_grip(wheels - 1, 0.05));
    const std::string past = test::error_of([&] { vehicle.set_road_grip(wheels, 1.0); });
    EXPECT_NE(past.find("wheel slot " + std::to_string(wheels) + " of " + std::to_string(wheels)),
              std::string::npos)
        << past;
    for (const double grip : {0.0, -0.5, std::numeric_limits<double>::quiet_NaN(),
                              std::numeric_limits<double>::infinity()}) {
        const std::string why = test::error_of([&] { vehicle.set_road_grip(1, grip); });
        EXPECT_NE(why.find("wheel slot 1: grip"), std::string::npos) << grip << ": " << why;
    }
}

// A wheel rolls on its ellipsoid's extent along the body's up axis, however the ellipsoid
// is turned: the gt's wheels, their 0.15 m width laid along y and turned a quarter about z
// so that the width is along x again, roll on 0.35 m as before (semi_axes.y was 0.15).
// Unturned wheels keep semi_axes.y bit for bit.
TEST(VehiclePhysics, AWheelRollsOnItsExtentAlongTheBodysUpAxis) {
    const CarSpec gt = CarSpec::preset("gt");
    CarSpec turned = gt;
    for (CarEllipsoid& e : turned.ellipsoids) {
        if (e.role == EllipsoidRole::body) continue;
        e.semi_axes = {e.semi_axes.y, e.semi_axes.x, e.semi_axes.z};
        e.orientation = glm::angleAxis(0.5 * std::numbers::pi, glm::dvec3(0.0, 0.0, 1.0));
    }
    const double speed = 10.0;
    const VehicleState plain = Vehicle(gt).rolling_at(speed);
    const VehicleState rolled = Vehicle(turned).rolling_at(speed);
    ASSERT_EQ(plain.wheels.size(), rolled.wheels.size());
    for (std::size_t w = 0; w < plain.wheels.size(); ++w) {
        EXPECT_EQ(plain.wheels[w].spin, speed / 0.35);
        EXPECT_NEAR(rolled.wheels[w].spin, speed / 0.35, 1e-12);
    }
}

// Skidpad: a flat 100 m radius circle at a slowly rising speed (0.15 m/s each second),
// steered by pure pursuit with yaw damping. The best lateral acceleration v^2 / r, over a
// second, while the car holds the circle within 2 m, against what the tyres' peak allows at
// the loads they carry then (downforce and load transfer across each axle included, each
// tyre's peak at its own load): each axle's lateral peaks over the share of the car's mass
// it turns, the weaker axle's.
// The rear differential is open here. The gt's limited-slip one sends more of the drive
// that holds the speed against drag to the slower inner wheel, whose push yaws the car out
// of the turn: the front tyres, at their peak, must also hold that moment, and the car
// turns about 6% less than its tyres allow. That is the differential's steady-state
// understeer, not the tyres' grip, which this test measures.
TEST(VehiclePhysics, SkidpadReachesThePeakGripTheTyresAllow) {
    CarSpec spec = CarSpec::preset("gt");
    spec.vehicle->rear_differential.kind = DifferentialKind::open;
    const double radius = 100.0;
    World world = world_with(test::flat_grid(260.0, 26), spec, radius, 0.0);
    drive(world, {}, 1.0);
    Car& car = world.car(0);
    const PointCar shape(spec, car.state().position.y);
    const double dt = world.settings().dt_update;

    double best = 0.0, reference = 0.0, target = 20.0;
    double window_a = 0.0, window_front = 0.0, window_rear = 0.0;
    int window = 0;
    for (int update = 0; update < 15000; ++update) {
        const RigidBodyState& s = car.state();
        const glm::dvec2 at(s.position.x, s.position.z);
        const double r = glm::length(at);
        if (r > radius + 5.0) break;  // beyond the limit: the car runs wide
        // Pure pursuit: a point 15 m ahead on the circle (driving clockwise seen from +Y).
        const double angle = std::atan2(at.y, at.x) + 15.0 / radius;
        const glm::dvec3 goal(radius * std::cos(angle), s.position.y, radius * std::sin(angle));
        const glm::dvec3 local = glm::conjugate(s.orientation) * (goal - s.position);
        const double curvature = 2.0 * local.x / (local.x * local.x + local.z * local.z);
        const double speed = car.speed();
        const double yaw_rate = glm::dot(s.angular_velocity, s.orientation * glm::dvec3(0, 1, 0));
        const double steer_angle =
            std::atan(curvature * shape.wheelbase) +
            0.5 * shape.wheelbase * (speed * curvature - yaw_rate) / std::max(speed, 5.0);
        target += 0.15 * dt;
        car.set_inputs({std::clamp(0.5 * (target - speed), 0.0, 1.0), 0.0,
                        std::clamp(steer_angle / spec.max_steer_angle, -1.0, 1.0)});
        world.update();

        // One-second windows: v^2 / r and each axle's lateral peaks at its tyres' loads.
        window_a += speed * speed / r;
        const Vehicle& vehicle = *car.vehicle();
        for (std::size_t i = 0; i < spec.ellipsoids.size(); ++i) {
            const int w = vehicle.wheel_slot(i);
            if (w < 0) continue;
            const double load = vehicle.telemetry()[static_cast<std::size_t>(w)].load;
            if (spec.ellipsoids[i].role == EllipsoidRole::front_wheel)
                window_front +=
                    peak_force(spec.vehicle->front_tyre, spec.vehicle->front_tyre.lateral, load);
            else
                window_rear +=
                    peak_force(spec.vehicle->rear_tyre, spec.vehicle->rear_tyre.lateral, load);
        }
        if (++window < 100) continue;
        const double m = spec.mass.mass;
        const double allowed = std::min(window_front / (m * shape.front_static),
                                        window_rear / (m * (1.0 - shape.front_static))) /
                               window;
        if (std::abs(r - radius) < 2.0 && window_a / window > best)
            best = window_a / window, reference = allowed;
        window = 0, window_a = window_front = window_rear = 0.0;
    }
    RecordProperty("skidpad_lateral_m_s2", std::to_string(best));
    RecordProperty("skidpad_reference_m_s2", std::to_string(reference));
    EXPECT_NEAR(best, reference, 0.03 * reference);
}

// Jolt's traction test: one driven wheel on ice (ice_grip: a twentieth of the grip), 30%
// throttle (about the gt's good tyre's grip; past the formula's) in first gear (an automatic box shifts up on the
// spinning wheel's speed, and each shift lets the engine spin up again), no traction control
// (it would brake the spinning wheel itself). The rear differential is the preset's own unless
// one is given.
double distance_with_a_rear_wheel_on_ice(std::string_view preset,
                                         std::optional<DifferentialSpec> rear = std::nullopt,
                                         double ice_grip = 0.05) {
    CarSpec spec = CarSpec::preset(preset);
    spec.vehicle->traction_control = false;
    spec.vehicle->gearbox.ratios.resize(1);
    if (rear) spec.vehicle->rear_differential = *rear;
    World world = world_with(test::flat_grid(-20.0, 20.0, -10.0, 300.0, 4, 31), spec);
    drive(world, {}, 1.0);
    Car& car = world.car(0);
    for (std::size_t i = 0; i < spec.ellipsoids.size(); ++i)
        if (spec.ellipsoids[i].role == EllipsoidRole::rear_wheel && spec.ellipsoids[i].center.x > 0)
            car.vehicle()->set_road_grip(static_cast<std::size_t>(car.vehicle()->wheel_slot(i)),
                                         ice_grip);
    const glm::dvec3 start = car.state().position;
    drive(world, {0.3, 0.0, 0.0}, 3.0);
    return glm::length(car.state().position - start);
}

// A clutch that can hold 1500 N m: a locking differential.
TEST(VehiclePhysics, LimitedSlipMovesTheCarWithAWheelOnIceAndTheOpenOneBarely) {
    const double limited = distance_with_a_rear_wheel_on_ice(
        "gt", DifferentialSpec{DifferentialKind::limited_slip, 1500.0, 0.3});
    const double open = distance_with_a_rear_wheel_on_ice("gt", DifferentialSpec{});
    RecordProperty("limited_slip_m", std::to_string(limited));
    RecordProperty("open_m", std::to_string(open));
    // The open differential passes the ice wheel's torque, a twentieth of a tyre's peak, to
    // the other wheel too: at most 0.5 m/s^2, about 2 m in 3 s after the launch.
    EXPECT_GT(limited, 10.0);
    EXPECT_LT(open, 0.25 * limited) << "limited slip " << limited << " m, open " << open << " m";
}

// The presets' own limited slip (gt 100 N m + 30% of the input torque, formula 50 N m + 30%)
// moves a car with a rear wheel on ice well beyond what the open differential gets, and no
// farther than with both rear wheels on the dry road: the ice wheel cannot add traction. (A
// locked differential is no bound: it drives the formula's dry wheel past its peak slip at
// 30% throttle, and a sliding tyre grips as its curve says, less than the peak: 8.1 m
// against the limited slip's 12.6.)
TEST(VehiclePhysics, ThePresetsOwnLimitedSlipPullsOffIce) {
    for (const std::string_view preset : {"gt", "formula"}) {
        ASSERT_EQ(CarSpec::preset(preset).vehicle->rear_differential.kind,
                  DifferentialKind::limited_slip)
            << preset;
        const double own = distance_with_a_rear_wheel_on_ice(preset);
        const double open = distance_with_a_rear_wheel_on_ice(preset, DifferentialSpec{});
        const double dry = distance_with_a_rear_wheel_on_ice(preset, std::nullopt, 1.0);
        RecordProperty(std::string(preset) + "_own_m", std::to_string(own));
        RecordProperty(std::string(preset) + "_open_m", std::to_string(open));
        RecordProperty(std::string(preset) + "_dry_m", std::to_string(dry));
        EXPECT_GT(own, 2.0 * open) << preset << ": own " << own << " m, open " << open << " m";
        EXPECT_LE(own, dry) << preset << ": own " << own << " m, dry " << dry;
    }
}

// A car added to a World already moving (a game spawning it into a race at speed) arrives
// as a teleported one does: rolling at the road's speed in a gear for it. Its vehicle model
// used to start at rest whatever the state, so a gt added at 30 m/s skidded on stopped
// wheels in first gear, lost 3.3 m/s in half a second and ran near its redline.
TEST(VehiclePhysics, ACarAddedMovingArrivesRollingAsATeleportedOne) {
    for (const std::string_view preset : {"gt", "formula"}) {
        SCOPED_TRACE(preset);
        const CarSpec spec = CarSpec::preset(preset);
        const double speed = 30.0;
        RigidBodyState moving =
            place_car_on_surface(*test::static_world_of(test::flat_grid(2000.0, 20)), spec,
                                 {0.0, 20.0, -900.0}, glm::dquat(1.0, 0.0, 0.0, 0.0));
        moving.linear_velocity = {0.0, 0.0, speed};
        World added(test::static_world_of(test::flat_grid(2000.0, 20)));
        added.add_car(spec, moving);
        World teleported(test::static_world_of(test::flat_grid(2000.0, 20)));
        teleported.add_car(spec, moving);
        teleported.teleport_car(0, moving);
        const double world_dt = added.settings().dt_update;

        const VehicleState& state = added.car(0).vehicle()->state();
        const VehicleState& expected = teleported.car(0).vehicle()->state();
        EXPECT_EQ(state.gear, expected.gear);
        ASSERT_EQ(state.wheels.size(), expected.wheels.size());
        for (std::size_t w = 0; w < state.wheels.size(); ++w)
            EXPECT_EQ(state.wheels[w].spin, expected.wheels[w].spin) << "wheel " << w;
        drive(added, {}, world_dt);
        for (const WheelTelemetry& wheel : added.car(0).vehicle()->telemetry())
            EXPECT_LT(std::abs(wheel.slip_ratio), 0.01);
        drive(added, {}, 0.5);
        drive(teleported, {}, 0.5 + world_dt);
        EXPECT_EQ(added.state_hash(), teleported.state_hash());
    }
}

// Braked wheels that stop, locked on the road without anti-lock or in the air over a
// crest, read as a speed the car has not lost: the box must not shift down on them into a
// gear the car's speed would drive past shift_up_rpm. It went 3-2-1 within 0.2 s at 43 m/s
// and, the brake released, dragged the engine to 9,000 rpm (locked) and 12,300 rpm (landed
// from a crest), far past the gt's 8,500 rpm redline, and coasted there.
TEST(VehiclePhysics, BrakedWheelsThatStopDoNotShiftTheBoxDownPastTheCarsSpeed) {
    CarSpec spec = CarSpec::preset("gt");
    spec.vehicle->anti_lock = false;
    const GearboxSpec& box = spec.vehicle->gearbox;
    const double radius = PointCar(spec, 0.0).radius;
    for (const double lift : {0.0, 1.5}) {
        SCOPED_TRACE(lift == 0.0 ? "locked on the road" : "stopped in the air");
        World world = world_with(test::flat_grid(3000.0, 30), spec, 0.0, -1400.0);
        drive(world, {}, 0.5);
        Car& car = world.car(0);
        RigidBodyState fast = car.state();
        fast.position.y += lift;
        fast.linear_velocity = fast.orientation * glm::dvec3(0.0, 0.0, 45.0);
        car.set_state(fast);
        const Vehicle& vehicle = *car.vehicle();
        double fastest_engine = 0.0, highest_ground_rpm = 0.0;
        bool stopped = false;
        for (int update = 0; update < 250; ++update) {
            drive(world, {0.0, update < 60 ? 1.0 : 0.0, 0.0}, world.settings().dt_update);
            for (const WheelState& wheel : vehicle.state().wheels) stopped |= wheel.spin == 0.0;
            const double ground_rpm = forward_speed(car) / radius *
                                      box.ratios[std::size_t(vehicle.state().gear - 1)] *
                                      box.final_drive * 60.0 / (2.0 * std::numbers::pi);
            highest_ground_rpm = std::max(highest_ground_rpm, ground_rpm);
            fastest_engine = std::max(fastest_engine, vehicle.engine_rpm());
        }
        EXPECT_TRUE(stopped) << "the brake should stop wheels";
        EXPECT_LE(highest_ground_rpm, box.shift_up_rpm);
        EXPECT_LE(fastest_engine, spec.vehicle->engine.redline_rpm);
        EXPECT_EQ(world.car_resets(0), 0u);
    }
}

// Without traction control a full-throttle launch spins the driven wheels. The box stays in
// first, the engine at its limiter, until the car itself is fast enough for second, and
// never comes down while the throttle is held (it went 1-2-1-2 when it shifted on the
// spinning wheels alone).
TEST(VehiclePhysics, ALaunchWithoutTractionControlDoesNotHuntGears) {
    for (const std::string_view preset : {"gt", "formula"}) {
        CarSpec spec = CarSpec::preset(preset);
        spec.vehicle->traction_control = false;
        World world = world_with(test::flat_grid(-20.0, 20.0, -10.0, 400.0, 4, 41), spec);
        drive(world, {}, 1.0);
        const Vehicle& vehicle = *world.car(0).vehicle();
        int downshifts = 0, highest = vehicle.state().gear;
        bool spun = false;
        for (int update = 0; update < 600; ++update) {
            const int before = vehicle.state().gear;
            drive(world, {1.0, 0.0, 0.0}, world.settings().dt_update);
            downshifts += vehicle.state().gear < before;
            highest = std::max(highest, vehicle.state().gear);
            for (const WheelTelemetry& wheel : vehicle.telemetry()) spun |= wheel.slip_ratio > 0.5;
        }
        EXPECT_TRUE(spun) << preset << ": the launch should spin the driven wheels";
        EXPECT_EQ(downshifts, 0) << preset;
        EXPECT_GE(highest, 2) << preset << ": six seconds of full throttle reach second";
    }
}

// Parked: 10 s after settling, the car has moved less than 1 mm and never faster than
// 1 mm/s.
void expect_parked(World& world, const CarInputs& inputs) {
    drive(world, inputs, 3.0);
    const glm::dvec3 parked = world.car(0).state().position;
    double fastest = 0.0;
    for (int i = 0; i < 1000; ++i) {
        drive(world, inputs, world.settings().dt_update);
        fastest = std::max(fastest, world.car(0).speed());
    }
    EXPECT_LT(glm::length(world.car(0).state().position - parked), 1e-3);
    EXPECT_LT(fastest, 1e-3);
    EXPECT_EQ(world.car_resets(0), 0u);
}

TEST(VehiclePhysics, StandsStillOnFlatGroundAndOnATwentyPercentSlopeWithBrakes) {
    for (const char* preset : {"gt", "formula"}) {
        SCOPED_TRACE(preset);
        const CarSpec spec = CarSpec::preset(preset);
        World flat = world_with(test::flat_grid(40.0, 8), spec);
        expect_parked(flat, {});

        TriangleMesh slope = test::flat_grid(40.0, 8);
        for (glm::dvec3& vertex : slope.vertices) vertex.y = 0.2 * vertex.z;  // rises to +Z
        World uphill = world_with(slope, spec);
        expect_parked(uphill, {0.0, 1.0, 0.0});
    }
}

// Coasting in gear at closed throttle on the flat near 40 km/h, the deceleration over one
// second against what drag, rolling resistance (c_rr of the load, downforce included) and
// the engine's drag through the gear (friction_torque rpm / redline) add up to, on the
// mass and the wheels' inertia (the clutch slips below launch_rpm, so the engine's inertia
// is not the car's). Drag alone, all there was before, gives the gt 0.044 m/s^2 there.
TEST(VehiclePhysics, ACoastingCarSlowsByDragRollingResistanceAndEngineBraking) {
    for (const char* preset : {"gt", "formula"}) {
        SCOPED_TRACE(preset);
        const CarSpec spec = CarSpec::preset(preset);
        const VehicleSpec& v = *spec.vehicle;
        World world = world_with(test::flat_grid(2000.0, 20), spec, 0.0, -900.0);
        drive(world, {}, 1.0);
        Car& car = world.car(0);
        while (forward_speed(car) < 45.0 / 3.6)
            drive(world, {1.0, 0.0, 0.0}, world.settings().dt_update);
        drive(world, {}, 0.5);  // the clutch and the tyres settle at closed throttle
        const double v0 = forward_speed(car);
        const int gear = car.vehicle()->state().gear;
        drive(world, {}, 1.0);
        const double v1 = forward_speed(car);
        ASSERT_EQ(car.vehicle()->state().gear, gear) << "a shift during the measurement";
        const double measured = v0 - v1;

        const double speed = 0.5 * (v0 + v1);
        const double r = PointCar(spec, 0.0).radius;
        const double ratio =
            v.gearbox.ratios[static_cast<std::size_t>(gear - 1)] * v.gearbox.final_drive;
        const double rpm = speed / r * ratio * 60.0 / (2.0 * std::numbers::pi);
        ASSERT_LT(rpm, v.gearbox.launch_rpm);
        const double aero = 0.5 * spec.air_density * speed * speed;
        const double drag = aero * spec.drag_area;
        const double rolling =
            v.rolling_resistance * (spec.mass.mass * g + aero * spec.downforce_area);
        const double engine = v.engine.friction_torque * rpm / v.engine.redline_rpm * ratio / r;
        const double expected =
            (drag + rolling + engine) / (spec.mass.mass + 4.0 * v.wheel_inertia / (r * r));
        RecordProperty(std::string(preset) + "_coast_m_s2", std::to_string(measured));
        RecordProperty(std::string(preset) + "_coast_reference_m_s2", std::to_string(expected));
        EXPECT_NEAR(measured, expected, 0.1 * expected) << "at " << speed * 3.6 << " km/h";
    }
}

// The force of the first wheel (a front one) of a car rolling at `rolling` m/s and sliding
// sideways at `sideways` m/s under `load` N in one sub-step of h s, its slips at that
// motion's steady state: lateral slip -V_y / V_x, slip ratio `slip_ratio` with the spin
// (1 + slip_ratio) times the rolling one; at `brake` (0 to 1) with no throttle.
TyreForce front_wheel_force(const CarSpec& spec, double rolling, double sideways, double load,
                            double h, double slip_ratio = 0.0, double brake = 0.0) {
    Vehicle vehicle(spec);
    VehicleState state = vehicle.rolling_at(rolling);
    for (WheelState& wheel : state.wheels) {
        wheel.lateral_slip = -sideways / rolling;
        wheel.slip_ratio = slip_ratio;  // kappa = (w R - V_x) / V_x
        wheel.spin *= 1.0 + slip_ratio;
    }
    vehicle.set_state(state);
    detail::VehicleAccess::begin_substep(vehicle, 0.0, brake, std::hypot(rolling, sideways),
                                         rolling, h);
    return detail::VehicleAccess::wheel_force(vehicle, 0, load, rolling, sideways, h);
}

// A front wheel sliding sideways at 5 and 20 m/s, rolling just below and just above
// low_speed, its lateral slip at that slide's steady state -V_y / V_x: its lateral force is
// the same either side (within 3%) and never more than the curve's for that slip. The
// damper below low_speed faded by the rolling speed alone pushed it to the ellipse's edge,
// the curve's peak D, up to 23% more than the sliding value just above.
TEST(VehiclePhysics, ASidewaysSlidingWheelGripsAsTheCurveSaysEitherSideOfLowSpeed) {
    const CarSpec spec = CarSpec::preset("gt");
    const Tyre tyre(spec.vehicle->front_tyre);
    ASSERT_EQ(spec.ellipsoids[0].role, EllipsoidRole::front_wheel);
    const double load = 3000.0, h = 0.002, low = spec.vehicle->low_speed;
    for (const double sideways : {5.0, 20.0}) {
        SCOPED_TRACE(sideways);
        double lateral[2];
        for (const int side : {0, 1}) {
            const double rolling = (side == 0 ? 0.99 : 1.01) * low;
            lateral[side] = front_wheel_force(spec, rolling, sideways, load, h).lateral;
            const double curve = tyre.force(0.0, -sideways / rolling, load).lateral;
            EXPECT_LE(std::abs(lateral[side]), std::abs(curve) * (1.0 + 1e-12))
                << "rolling at " << rolling << " m/s";
        }
        RecordProperty("sliding_" + std::to_string(static_cast<int>(sideways)) + "_m_s_below_n",
                       std::to_string(lateral[0]));
        RecordProperty("sliding_" + std::to_string(static_cast<int>(sideways)) + "_m_s_above_n",
                       std::to_string(lateral[1]));
        EXPECT_NEAR(lateral[0], lateral[1], 0.03 * std::abs(lateral[1]));
    }
}

// A wheel sliding sideways slowly, its contact's whole speed below low_speed (0.5 m/s rolling
// and 1 to 2.5 m/s sideways), its lateral slip at that slide's steady state -V_y / V_x: the
// damper acts there, but the lateral force stays the curve's for that slip. Filling the
// friction ellipse, it was the peak D, 21% above the curve at 2 m/s (car review 3).
TEST(VehiclePhysics, ASlowSidewaysSlideGripsAsTheCurveSays) {
    for (const char* preset : {"gt", "formula"}) {
        const CarSpec spec = CarSpec::preset(preset);
        const Tyre tyre(spec.vehicle->front_tyre);
        const double load = 3000.0, h = 0.002, rolling = 0.5;
        ASSERT_LT(std::hypot(rolling, 2.5), spec.vehicle->low_speed) << preset;
        for (const double sideways : {1.0, 1.5, 2.0, 2.5}) {
            SCOPED_TRACE(std::string(preset) + " sliding at " + std::to_string(sideways));
            const double lateral = front_wheel_force(spec, rolling, sideways, load, h).lateral;
            const double curve = tyre.force(0.0, -sideways / rolling, load).lateral;
            ASSERT_LT(curve, 0.0);
            EXPECT_LE(std::abs(lateral), std::abs(curve) * (1.0 + 1e-12));
            EXPECT_GE(std::abs(lateral), std::abs(curve) * (1.0 - 1e-12));
        }
    }
}

// The preset without its rolling resistance, which the tyre's longitudinal force carries.
CarSpec without_rolling_resistance(const char* preset) {
    CarSpec spec = CarSpec::preset(preset);
    spec.vehicle->rolling_resistance = 0.0;
    return spec;
}

// A preset without rolling resistance, its front tyre under 3000 N rolling at 0.5 m/s (below
// low_speed: the damper acts) in sub-steps of 2 ms.
struct SlowFrontWheel {
    explicit SlowFrontWheel(const char* preset)
        : spec(without_rolling_resistance(preset)),
          tyre(spec.vehicle->front_tyre),
          peaks(tyre.peaks(load)) {}
    static constexpr double load = 3000.0, h = 0.002, rolling = 0.5;
    CarSpec spec;
    Tyre tyre;
    TyreForce peaks;  ///< the friction ellipse's semi-axes
};

// The share of the friction ellipse with semi-axes `peaks` that a force uses.
double ellipse_share(const TyreForce& force, const TyreForce& peaks) {
    return std::hypot(force.longitudinal / peaks.longitudinal, force.lateral / peaks.lateral);
}

// A wheel braked past its peak slip ratio, up to locked, while it rolls at 0.5 m/s, and
// sliding sideways too or not: the brake (through the damper's spin) and the lateral damper
// push the force past the curve's, but it uses the share of the friction ellipse the curve
// uses for those slips, no more (braked alone: the curve's force), as the sideways slide
// does. At 1.5 m/s sideways the anti-lock lets the brake off; the lateral damper alone
// reaches the limit there.
TEST(VehiclePhysics, ASlowBrakedSlideUsesTheCurvesShareOfTheEllipse) {
    for (const char* preset : {"gt", "formula"}) {
        const SlowFrontWheel w(preset);
        for (const double slip_ratio : {-1.5 * w.tyre.peak_slip_ratio(), -0.5, -1.0})
            for (const double sideways : {0.0, 0.02, 0.5, 1.5}) {
                SCOPED_TRACE(std::string(preset) + " slip ratio " + std::to_string(slip_ratio) +
                             ", sliding at " + std::to_string(sideways));
                ASSERT_GT(w.tyre.normalised(slip_ratio, -sideways / w.rolling).combined, 1.0);
                const TyreForce force =
                    front_wheel_force(w.spec, w.rolling, sideways, w.load, w.h, slip_ratio, 1.0);
                const TyreForce curve = w.tyre.force(slip_ratio, -sideways / w.rolling, w.load);
                const double used = ellipse_share(force, w.peaks);
                const double curve_uses = ellipse_share(curve, w.peaks);
                EXPECT_LE(used, curve_uses * (1.0 + 1e-12));
                EXPECT_GE(used, curve_uses * (1.0 - 1e-12));
                EXPECT_LT(force.longitudinal, 0.0);
                if (sideways > 0.0) {
                    EXPECT_LT(force.lateral, 0.0);
                } else {
                    EXPECT_EQ(force.lateral, 0.0);
                }
            }
    }
}

// Through the peak slip, where the damper's room shrinks from the whole ellipse to the
// curve's share: a part in 1e-7 of the peak slip either side, a braked wheel and a wheel
// sliding sideways both get the peak force, within a part in 1e-6.
TEST(VehiclePhysics, TheSlowTyreForceIsContinuousThroughThePeakSlip) {
    for (const char* preset : {"gt", "formula"}) {
        const SlowFrontWheel w(preset);
        for (const double side : {-1.0, 1.0}) {
            SCOPED_TRACE(std::string(preset) + (side < 0 ? " below" : " above") + " the peak");
            const double at = 1.0 + side * 1e-7;
            const TyreForce braked = front_wheel_force(w.spec, w.rolling, 0.0, w.load, w.h,
                                                       -at * w.tyre.peak_slip_ratio(), 1.0);
            const TyreForce sliding = front_wheel_force(
                w.spec, w.rolling, at * w.tyre.peak_lateral_slip() * w.rolling, w.load, w.h);
            EXPECT_NEAR(braked.longitudinal, -w.peaks.longitudinal, 1e-6 * w.peaks.longitudinal);
            EXPECT_NEAR(sliding.lateral, -w.peaks.lateral, 1e-6 * w.peaks.lateral);
        }
    }
}

// Flat ground with a wall across +Z at z = wall_z, facing a car that comes from z < wall_z.
TriangleMesh ground_with_wall(double wall_z) {
    TriangleMesh scene = test::flat_grid(200.0, 40);
    const TriangleMesh barrier = test::wall(wall_z, 20.0, 3.0);
    const auto base = static_cast<std::uint32_t>(scene.vertices.size());
    scene.vertices.insert(scene.vertices.end(), barrier.vertices.begin(), barrier.vertices.end());
    for (auto t : barrier.triangles)
        scene.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
    return scene;
}

// Whether the car is in reverse gear; true for the arcade car, which has no gears.
bool in_reverse_gear_if_geared(const Car& car) {
    return !car.vehicle() || car.vehicle()->state().gear == VehicleState::reverse_gear;
}

// A car driven nose first into a wall backs away from it at full reverse (throttle -1):
// the vehicle model through its reverse gear, the arcade car by its reverse drive force up
// to max_reverse_speed. Clamped to 0, as the throttle was, it would stay at the wall.
TEST(VehiclePhysics, EveryCarBacksAwayFromAWallAtFullReverse) {
    for (const char* preset : {"arcade", "gt", "formula"}) {
        SCOPED_TRACE(preset);
        const CarSpec spec = CarSpec::preset(preset);
        World world = world_with(ground_with_wall(6.0), spec);
        drive(world, {0.3, 0.0, 0.0}, 4.0);
        Car& car = world.car(0);
        const double at_wall = car.state().position.z;
        ASSERT_GT(at_wall, 6.0 - 2.7) << "the car did not reach the wall";
        ASSERT_LT(std::abs(forward_speed(car)), 0.2) << "the car is not stopped by the wall";

        drive(world, {-1.0, 0.0, 0.0}, 3.0);
        const double backed = at_wall - car.state().position.z;
        RecordProperty(std::string(preset) + "_reversed_in_3_s_m", std::to_string(backed));
        EXPECT_GT(backed, 5.0);
        EXPECT_LT(forward_speed(car), -2.0);
        EXPECT_TRUE(in_reverse_gear_if_geared(car));
        EXPECT_EQ(world.car_resets(0), 0u);
        // A snapshot file carries the reverse gear.
        world.restore_state(decode_snapshot(encode_snapshot(world.save_state())).world);
        EXPECT_TRUE(in_reverse_gear_if_geared(car));
        if (spec.vehicle) continue;
        // The arcade car's reverse drive fades to none at max_reverse_speed.
        drive(world, {-1.0, 0.0, 0.0}, 3.0);
        EXPECT_LE(-forward_speed(car), spec.max_reverse_speed);
        EXPECT_GT(-forward_speed(car), 0.9 * spec.max_reverse_speed);
    }
}

// Reverse engages only once the car is nearly stopped: at 20 m/s a negative throttle is a
// closed throttle (the car coasts exactly as at throttle 0, in a forward gear); braked to a
// stop with it held, the car then drives backwards.
TEST(VehiclePhysics, ANegativeThrottleAtSpeedCoastsAndReversesOnlyOnceStopped) {
    for (const char* preset : {"arcade", "gt"}) {
        SCOPED_TRACE(preset);
        const CarSpec spec = CarSpec::preset(preset);
        World coasting = world_with(test::flat_grid(2000.0, 20), spec, 0.0, -900.0);
        World reversing = world_with(test::flat_grid(2000.0, 20), spec, 0.0, -900.0);
        for (World* world : {&coasting, &reversing}) {
            drive(*world, {}, 1.0);
            while (forward_speed(world->car(0)) < 20.0)
                drive(*world, {1.0, 0.0, 0.0}, world->settings().dt_update);
        }
        drive(coasting, {0.0, 0.0, 0.0}, 1.0);
        drive(reversing, {-1.0, 0.0, 0.0}, 1.0);
        Car& car = reversing.car(0);
        if (spec.vehicle) {
            EXPECT_GE(car.vehicle()->state().gear, 1);
        }
        EXPECT_GT(forward_speed(car), 19.0);
        EXPECT_EQ(forward_speed(car), forward_speed(coasting.car(0)));

        while (forward_speed(car) > 0.1)
            drive(reversing, {-1.0, 1.0, 0.0}, reversing.settings().dt_update);
        drive(reversing, {-1.0, 0.0, 0.0}, 2.0);
        EXPECT_LT(forward_speed(car), -2.0);
        EXPECT_TRUE(in_reverse_gear_if_geared(car));
        // And forwards again once the reversing car is nearly stopped.
        while (forward_speed(car) < -0.1)
            drive(reversing, {0.0, 1.0, 0.0}, reversing.settings().dt_update);
        drive(reversing, {1.0, 0.0, 0.0}, 2.0);
        EXPECT_GT(forward_speed(car), 2.0);
        if (spec.vehicle) {
            EXPECT_EQ(car.vehicle()->state().gear, 1);
        }
        EXPECT_EQ(reversing.car_resets(0), 0u);
    }
}

TEST(VehiclePhysics, SnapshotsCarryWheelsGearAndClutchAndReplayBitForBit) {
    const CarSpec spec = CarSpec::preset("gt");
    World world = world_with(test::flat_grid(400.0, 20), spec);
    drive(world, {1.0, 0.0, 0.05}, 4.0);
    const VehicleState saved_vehicle = world.car(0).vehicle()->state();
    EXPECT_GT(saved_vehicle.gear, 1);
    EXPECT_NE(saved_vehicle.wheels[0].spin, 0.0);

    const WorldSnapshot snapshot = world.save_state();
    ASSERT_TRUE(snapshot.cars[0].vehicle.has_value());
    EXPECT_EQ(*snapshot.cars[0].vehicle, saved_vehicle);
    std::vector<std::uint64_t> hashes;
    for (int i = 0; i < 100; ++i) {
        drive(world, {0.6, 0.0, -0.2}, world.settings().dt_update);
        hashes.push_back(world.state_hash());
    }

    // Restored in place and, through the snapshot file, in a fresh world: the same updates.
    const SnapshotFile file = decode_snapshot(encode_snapshot(snapshot));
    World fresh = world_with(test::flat_grid(400.0, 20), spec);
    for (const WorldSnapshot* source : {&snapshot, &file.world}) {
        for (World* target : {&world, &fresh}) {
            target->restore_state(*source);
            EXPECT_EQ(target->car(0).vehicle()->state(), saved_vehicle);
            for (int i = 0; i < 100; ++i) {
                drive(*target, {0.6, 0.0, -0.2}, target->settings().dt_update);
                ASSERT_EQ(target->state_hash(), hashes[i]) << "update " << i;
            }
        }
    }

    // The wheels are state: a different spin is a different hash, and a snapshot of a
    // vehicle without its state is refused.
    World other = world_with(test::flat_grid(400.0, 20), spec);
    other.restore_state(snapshot);
    VehicleState spun = saved_vehicle;
    spun.wheels[0].spin += 1.0;
    const std::uint64_t before = other.state_hash();
    other.car(0).set_vehicle_state(spun);
    EXPECT_NE(other.state_hash(), before);
    WorldSnapshot stripped = snapshot;
    stripped.cars[0].vehicle.reset();
    EXPECT_THROW(other.restore_state(stripped), Error);
}

}  // namespace
}  // namespace trackphys
