#include "trackphys/dynamics/car.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <sstream>
#include <string>
#include <utility>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

#include "dynamics/body_axes.hpp"
#include "dynamics/wheel_force.hpp"
#include "trackphys/assert.hpp"
#include "trackphys/error.hpp"
#include "trackphys/math/types.hpp"
#include "vehicle/vehicle_access.hpp"

namespace trackphys {
namespace {

void check_state(const RigidBodyState& state) {
    if (!is_finite(state.position)) throw Error("car state: position is not finite");
    if (!is_finite(state.orientation) || !(glm::length(state.orientation) > 0.5))
        throw Error("car state: orientation must be a finite unit quaternion");
    if (!is_finite(state.linear_velocity)) throw Error("car state: linear_velocity is not finite");
    if (!is_finite(state.angular_velocity))
        throw Error("car state: angular_velocity is not finite");
}

double clamp_input(const char* name, double value, double low, double high) {
    if (std::isnan(value)) throw Error(std::string("car inputs: ") + name + " is NaN");
    return std::clamp(value, low, high);
}

// The inputs clamped to their ranges; throws for NaN.
CarInputs clamped(const CarInputs& in) {
    return {clamp_input("throttle", in.throttle, -1.0, 1.0),
            clamp_input("brake", in.brake, 0.0, 1.0), clamp_input("steer", in.steer, -1.0, 1.0)};
}

}  // namespace

Car::Car(CarSpec spec, const RigidBodyState& initial_state) : spec_(std::move(spec)) {
    if (std::string why = spec_.validate(); !why.empty()) throw Error(why);
    auto shape = std::make_shared<Shape>();
    for (const CarEllipsoid& e : spec_.ellipsoids) {
        const Ellipsoid& body =
            shape->body.emplace_back(Ellipsoid(e.center, e.orientation, e.semi_axes)).ellipsoid();
        shape->parts.push_back(
            {e.role, spec_.deep_contact_fraction * body.sorted_radii().z * (1.0 - 1e-12)});
        if (e.role != EllipsoidRole::body) shape->wheel_end = shape->parts.size();
        suspension_.push_back(0.0);
        // A wheel rises along the body's up axis by up to the suspension's travel (lifted):
        // the sphere holds it at both ends, and so all the way between.
        const double raised =
            e.role == EllipsoidRole::body
                ? 0.0
                : glm::length(e.center + glm::dvec3(0.0, spec_.suspension.travel, 0.0));
        bounding_radius_ = std::max(
            bounding_radius_, std::max(glm::length(e.center), raised) + body.bounding_radius());
        wheels_ += e.role != EllipsoidRole::body;
        front_wheels_ += e.role == EllipsoidRole::front_wheel;
    }
    shape_ = std::move(shape);
    if (spec_.vehicle) vehicle_.emplace(spec_);
    // After the vehicle model, which set_state starts rolling at the car's speed.
    set_state(initial_state);
    take_inputs(inputs_);
}

bool Car::Shape::same_bits(const Shape& other) const {
    // Bits, not values: a -0.0 for a 0.0 could change the sign of a zero downstream.
    static_assert(sizeof(Ellipsoid) == 22 * sizeof(double), "an Ellipsoid has no padding");
    if (body.size() != other.body.size()) return false;
    for (std::size_t i = 0; i < body.size(); ++i)
        if (std::memcmp(&body[i].ellipsoid(), &other.body[i].ellipsoid(), sizeof(Ellipsoid)) != 0 ||
            parts[i].role != other.parts[i].role ||
            std::bit_cast<std::uint64_t>(parts[i].deep_contact_depth) !=
                std::bit_cast<std::uint64_t>(other.parts[i].deep_contact_depth))
            return false;
    return true;
}

bool Car::share_ellipsoids_with(const Car& other) {
    if (shape_ != other.shape_ && shape_->same_bits(*other.shape_)) shape_ = other.shape_;
    return shape_ == other.shape_;
}

void Car::set_state(const RigidBodyState& state) {
    check_state(state);
    state_ = state;
    // Normalising is not idempotent: a unit quaternion to rounding, a car's own state handed
    // back, keeps its bits (docs/design.md#determinism).
    const double norm2 = glm::dot(state.orientation, state.orientation);
    if (!(std::abs(norm2 - 1.0) <= 8.0 * std::numeric_limits<double>::epsilon()))
        state_.orientation = glm::normalize(state.orientation);
    std::fill(suspension_.begin(), suspension_.end(), 0.0);
    if (vehicle_)
        vehicle_->set_state(vehicle_->rolling_at(
            glm::dot(state_.linear_velocity, state_.orientation * glm::dvec3(0.0, 0.0, 1.0))));
}

void Car::set_inputs(const CarInputs& inputs) { take_inputs(clamped(inputs)); }

// The steered heading changes with the inputs only, not every sub-step of every wheel.
void Car::take_inputs(const CarInputs& inputs) {
    inputs_ = inputs;
    // Body +Z is forward; front wheels turn about body +Y (positive steer = left).
    const double angle = steer_angle();
    steered_heading_ = glm::dvec3(std::sin(angle), 0.0, std::cos(angle));
}

void Car::check_restore(const RigidBodyState& state, const CarInputs& inputs,
                        std::span<const double> suspension) const {
    check_state(state);
    if (!(std::abs(glm::length(state.orientation) - 1.0) <= 1e-6))
        throw Error("car state: orientation is not a unit quaternion");
    const CarInputs in_range = clamped(inputs);
    if (in_range.throttle != inputs.throttle || in_range.brake != inputs.brake ||
        in_range.steer != inputs.steer)
        throw Error("car inputs: out of range (throttle and steer -1..1, brake 0..1)");
    check_suspension(suspension);
}

void Car::restore(const RigidBodyState& state, const CarInputs& inputs,
                  std::span<const double> suspension) {
    check_restore(state, inputs, suspension);
    std::copy(suspension.begin(), suspension.end(), suspension_.begin());
    state_ = state;
    take_inputs(inputs);
}

void Car::set_suspension(std::span<const double> travel) {
    check_suspension(travel);
    std::copy(travel.begin(), travel.end(), suspension_.begin());
}

void Car::check_suspension(std::span<const double> travel) const {
    if (travel.size() != suspension_.size())
        throw Error("car suspension: " + std::to_string(travel.size()) + " values for " +
                    std::to_string(suspension_.size()) + " ellipsoids");
    for (std::size_t i = 0; i < travel.size(); ++i) {
        const double limit =
            spec_.ellipsoids[i].role == EllipsoidRole::body ? 0.0 : spec_.suspension.travel;
        if (!(travel[i] >= 0.0 && travel[i] <= limit))
            throw Error("car suspension: ellipsoid " + std::to_string(i) +
                        "'s travel must be in [0, " + exact_text(limit) + "] m, got " +
                        exact_text(travel[i]));
    }
}

void Car::set_vehicle_state(const VehicleState& state) {
    check_vehicle_state(state);
    vehicle_->set_state(state);
}

void Car::check_vehicle_state(const VehicleState& state) const {
    if (!vehicle_) throw Error("car: the arcade car has no vehicle state to set");
    vehicle_->check_state(state);
}

// The sub-step's small laws are inline: Car is exported and the library built with -fPIC,
// where a member that is not inline may be interposed, so it is called, never compiled in.
inline ContactMaterial Car::wheel_material(Axle axle) const {
    ContactMaterial material = spec_.wheel_contact;
    if (axle == Axle::rear) material.friction *= spec_.rear_grip_factor;
    return material;
}

// Drive is a constant force up to the speed where the power limit takes over: F = P / v.
inline double Car::drive_available(double speed_now) const {
    return std::min(spec_.max_drive_force, spec_.max_drive_power / std::max(speed_now, 1.0));
}

inline double Car::reverse_available(double speed_now, double forward_speed) const {
    if (!(forward_speed < CarSpec::reverse_engage_speed && spec_.max_reverse_speed > 0.0))
        return 0.0;
    return drive_available(speed_now) *
           std::clamp(1.0 + forward_speed / spec_.max_reverse_speed, 0.0, 1.0);
}

inline WheelCommand Car::wheel_command(Axle axle, const glm::dvec3& heading,
                                       const ContactMaterial& material, double axle_normal_force,
                                       double available) const {
    WheelCommand command;
    command.heading = heading;
    const bool front = axle == Axle::front;
    // Drive and brake are split between the axles, then evenly between an axle's wheels.
    const int axle_wheels = std::max(front ? front_wheels_ : wheels_ - front_wheels_, 1);
    const double drive_share = front ? spec_.front_drive_share : 1.0 - spec_.front_drive_share;
    const double brake_share = front ? spec_.front_brake_share : 1.0 - spec_.front_brake_share;
    command.drive_force = inputs_.throttle * available * drive_share / axle_wheels;
    command.brake_force = inputs_.brake * spec_.max_brake_force * brake_share / axle_wheels;
    command.max_along_force = spec_.traction_limit * material.friction * axle_normal_force;
    return command;
}

void Car::advance(std::span<const Contact> deepest, const glm::dvec3& gravity, double h,
                  std::span<const double> grip) {
    TP_ASSERT(grip.empty() || grip.size() == deepest.size(), "one grip per ellipsoid, or none");
    resolve_deep_contacts(deepest);
    // The impulses turn the velocities only: the axes hold until integrate.
    const detail::BodyAxes axes(state_.orientation);
    WheelLoads wheel_loads;
    const AxleLoads least_loads = measure_wheel_loads(deepest, wheel_loads);
    const Wrench wrench = vehicle_ ? vehicle_wrench(deepest, grip, wheel_loads, axes, h)
                                   : contact_wrench(deepest, grip, wheel_loads, least_loads, axes);
    update_suspension(deepest, wheel_loads, axes.up, h);
    trackphys::integrate(state_, spec_.mass, wrench, gravity, h);
}

Car::AxleLoads Car::measure_wheel_loads(std::span<const Contact> deepest,
                                        WheelLoads& wheel_loads) const {
    AxleLoads least_loads = {std::numeric_limits<double>::infinity(),
                             std::numeric_limits<double>::infinity()};
    // The parts through a pointer read once: a store to wheel_loads could alias shape_.
    const Part* parts = shape_->parts.data();
    const std::size_t wheel_end = std::min(deepest.size(), shape_->wheel_end);
    for (std::size_t i = 0; i < wheel_end; ++i) {
        if (parts[i].role == EllipsoidRole::body) continue;
        WheelLoad& wheel = wheel_loads[i];
        wheel.velocity = point_velocity(state_, deepest[i].point);
        wheel.load =
            normal_force(spec_.wheel_contact, deepest[i].depth, deepest[i].normal, wheel.velocity);
        double& least = least_loads[static_cast<int>(axle_of(parts[i].role))];
        least = std::min(least, wheel.load);
    }
    return least_loads;
}

Wrench Car::contact_wrench(std::span<const Contact> deepest, std::span<const double> grip,
                           const WheelLoads& wheel_loads, const AxleLoads& least_loads,
                           const detail::BodyAxes& axes) const {
    // Every wheel of an axle rolls with the same material and command: two of each per
    // sub-step, not one per wheel. The speed serves the aerodynamics too.
    const double speed_now = speed();
    const glm::dvec3& forward = axes.forward;
    // A negative throttle times the force backwards drives the car backwards.
    const double available =
        inputs_.throttle < 0.0
            ? reverse_available(speed_now, glm::dot(state_.linear_velocity, forward))
            : drive_available(speed_now);
    const ContactMaterial materials[2] = {wheel_material(Axle::front), wheel_material(Axle::rear)};
    const WheelCommand commands[2] = {
        wheel_command(Axle::front, wheel_heading(Axle::front, forward), materials[0],
                      least_loads[0], available),
        wheel_command(Axle::rear, forward, materials[1], least_loads[1], available)};
    Wrench wrench;
    const Part* parts = shape_->parts.data();
    for (std::size_t i = 0; i < deepest.size(); ++i) {
        const Contact& contact = deepest[i];
        if (!(contact.depth > 0.0)) continue;
        const EllipsoidRole role = parts[i].role;
        const int axle = static_cast<int>(axle_of(role));
        // A wheel's load and point velocity are this sub-step's, from measure_wheel_loads
        // (its materials differ from spec_.wheel_contact in friction only).
        // The surface scales the axle's friction and traction limit for this wheel alone.
        const double surface_grip = grip.empty() ? 1.0 : grip[i];
        glm::dvec3 force;
        if (role == EllipsoidRole::body) {
            force = body_contact_force(on_surface(spec_.body_contact, surface_grip), contact.depth,
                                       contact.normal, point_velocity(state_, contact.point));
        } else {
            WheelCommand command = commands[axle];
            command.max_along_force *= surface_grip;
            force = detail::pressed_wheel_force(on_surface(materials[axle], surface_grip),
                                                wheel_loads[i].load, contact.normal,
                                                wheel_loads[i].velocity, command);
        }
        wrench.add_at_point(force, contact.point, state_.position);
    }
    add_aero_force(wrench, speed_now, axes.forward, axes.down);
    return wrench;
}

void Car::update_suspension(std::span<const Contact> deepest, const WheelLoads& wheel_loads,
                            const glm::dvec3& up, double h) {
    const Suspension& spring = spec_.suspension;
    if (vehicle_) detail::VehicleAccess::measure_anti_roll(*vehicle_, suspension_);
    const Part* parts = shape_->parts.data();
    const std::size_t wheel_end = std::min(deepest.size(), shape_->wheel_end);
    for (std::size_t i = 0; i < wheel_end; ++i) {
        if (parts[i].role == EllipsoidRole::body) continue;
        double lift = wheel_loads[i].load * glm::dot(deepest[i].normal, up);
        if (vehicle_)
            lift -= vehicle_->anti_roll_force(static_cast<std::size_t>(vehicle_->wheel_slot(i)));
        // Massless wheel: the damper passes what the spring does not hold.
        const double rate = (lift - spring.stiffness * suspension_[i]) / spring.damping;
        suspension_[i] = std::clamp(suspension_[i] + h * rate, 0.0, spring.travel);
    }
}

void Car::resolve_deep_contacts(std::span<const Contact> deepest) {
    for (std::size_t i = 0; i < deepest.size(); ++i) {
        const Contact& contact = deepest[i];
        // The half-extent is at least the smallest radius, and that much less an ulp-sized
        // margin for its rounding keeps this test exactly the one below: an ordinary
        // contact (a wheel 1 cm deep) skips the rotation and the square root.
        if (!(contact.depth > shape_->parts[i].deep_contact_depth)) continue;
        const Ellipsoid& e = shape_->body[i].ellipsoid();
        // The ellipsoid's half-extent along the contact normal (its support h(n)).
        const glm::dvec3 n_local =
            glm::conjugate(state_.orientation) * contact.normal * e.sorted_axes();
        const double extent = glm::length(e.sorted_radii() * n_local);
        if (!(contact.depth > spec_.deep_contact_fraction * extent)) continue;
        const glm::dvec3 lever = contact.point - state_.position;
        const double approach = glm::dot(point_velocity(state_, contact.point), contact.normal);
        if (approach >= 0.0) continue;
        // Impulse j n with the point's normal velocity brought to zero:
        // j = -v_n / (1/m + n . ((I^-1 (r x n)) x r)).
        const glm::dvec3 body_axis =
            glm::conjugate(state_.orientation) * glm::cross(lever, contact.normal);
        const glm::dvec3 turn = state_.orientation * (body_axis / spec_.mass.principal_inertia);
        const double inverse_mass =
            1.0 / spec_.mass.mass + glm::dot(contact.normal, glm::cross(turn, lever));
        const double j = -approach / inverse_mass;
        state_.linear_velocity += contact.normal * (j / spec_.mass.mass);
        state_.angular_velocity += turn * j;
    }
}

void Car::throw_no_ellipsoid(std::size_t i) const {
    throw Error("the car has no ellipsoid " + std::to_string(i) + " (it has " +
                std::to_string(shape_->body.size()) + ")");
}

Car::Velocities Car::pushed(const glm::dvec3& impulse, const glm::dvec3& point) const {
    const glm::dvec3 angular = glm::cross(point - state_.position, impulse);
    const glm::dvec3 body_angular = glm::conjugate(state_.orientation) * angular;
    return {state_.linear_velocity + impulse / spec_.mass.mass,
            state_.angular_velocity +
                state_.orientation * (body_angular / spec_.mass.principal_inertia)};
}

void Car::push(const glm::dvec3& impulse, const glm::dvec3& point) {
    const Velocities v = pushed(impulse, point);
    state_.linear_velocity = v.linear;
    state_.angular_velocity = v.angular;
}

void Car::apply_impulse(const glm::dvec3& impulse, const glm::dvec3& point) {
    const Velocities v = pushed(impulse, point);
    // Also what overflows: a finite impulse far from the centre can give an infinite spin.
    if (!is_finite(v.linear) || !is_finite(v.angular)) {
        std::ostringstream why;
        why << "Car::apply_impulse: impulse (" << impulse.x << ", " << impulse.y << ", "
            << impulse.z << ") N s at point (" << point.x << ", " << point.y << ", " << point.z
            << ") m leaves the car's velocity not finite; the car is unchanged";
        throw Error(why.str());
    }
    state_.linear_velocity = v.linear;
    state_.angular_velocity = v.angular;
}

double Car::inverse_mass_along(const glm::dvec3& normal, const glm::dvec3& point) const {
    const glm::dvec3 lever = point - state_.position;
    const glm::dvec3 body_axis = glm::conjugate(state_.orientation) * glm::cross(lever, normal);
    const glm::dvec3 turn = state_.orientation * (body_axis / spec_.mass.principal_inertia);
    return 1.0 / spec_.mass.mass + glm::dot(normal, glm::cross(turn, lever));
}

}  // namespace trackphys
