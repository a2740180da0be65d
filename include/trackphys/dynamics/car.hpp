#pragma once

#include <array>
#include <cstddef>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/vec3.hpp>

#include "trackphys/detail/body_ellipsoid.hpp"
#include "trackphys/dynamics/car_spec.hpp"
#include "trackphys/dynamics/contact_force.hpp"
#include "trackphys/dynamics/rigid_body.hpp"
#include "trackphys/export.hpp"
#include "trackphys/geometry/aabb.hpp"
#include "trackphys/geometry/contact.hpp"
#include "trackphys/geometry/ellipsoid.hpp"
#include "trackphys/math/types.hpp"
#include "trackphys/vehicle/vehicle.hpp"

namespace trackphys {

namespace detail {
struct BodyAxes;   // src/dynamics/body_axes.hpp: the sub-step's body axes
struct CarAccess;  // src/dynamics/car_access.hpp: World's private steps of a car
}  // namespace detail

/// The driver's controls. Out-of-range values are clamped by Car::set_inputs; NaN is
/// rejected.
///
/// Reverse is a negative throttle: -1 asks for the full drive backwards. It drives the car
/// backwards only once the car is nearly stopped or already rolling backwards (forward
/// speed below CarSpec::reverse_engage_speed); while the car rolls forward faster than that
/// a negative throttle is a closed throttle, and the car coasts (as an automatic gearbox
/// refuses reverse at speed). A vehicle model in reverse gear likewise takes a positive
/// throttle as a closed one until the car is nearly stopped or rolling forwards; the
/// arcade car, which has no gear, drives forwards at any speed under a positive throttle
/// (a spun car sliding backwards can drive out of it). A game that maps one key to
/// "brake, then reverse" sends brake while the car rolls forward and a negative throttle
/// once it has stopped.
struct CarInputs {
    /// -1..1, fraction of the available drive force: > 0 forwards, < 0 in reverse (see
    /// above); the vehicle model's engine sees its size as the pedal.
    double throttle = 0.0;
    double brake = 0.0;  ///< 0..1, fraction of the brake force
    double steer = 0.0;  ///< -1..1, +1 = full left
};

/// A car: its spec (validated), its rigid-body state and its inputs, and the force laws
/// that turn the contacts of its ellipsoids into a wrench on the body.
///
/// The public surface is what a game does to a car, most often to a World's through
/// World::car(i): set its inputs, move it (set_state), set its vehicle state or road grip,
/// push it (apply_impulse), and read its spec, state, suspension and telemetry. What only
/// World::update and World::restore_state may do (the sub-step, the restore of a snapshot's
/// bits, the suspension's reset, sharing and placing the ellipsoids) is private, reached
/// through detail::CarAccess (src/dynamics/car_access.hpp), which the World and the tests
/// use: a car stepped outside World::update would leave the world's time and contacts
/// behind it. A car can be copied (a copy is the game's own, apart from any world) but not
/// assigned: a World keeps per-ellipsoid lists sized for each car it added, and a car of
/// another spec assigned over one of them would break them. A car moved from may only be
/// destroyed: its body ellipsoids went with the move.
class TRACKPHYS_API Car {
  public:
    /// Starts as set_state(initial_state) leaves a car: a vehicle model rolling at the
    /// state's speed. Throws trackphys::Error with CarSpec::validate()'s message for an
    /// invalid spec, or naming the field of a non-finite initial state.
    Car(CarSpec spec, const RigidBodyState& initial_state);
    Car(const Car&) = default;
    Car(Car&&) noexcept = default;
    Car& operator=(const Car&) = delete;  // see the class notes
    Car& operator=(Car&&) = delete;
    ~Car() = default;

    const CarSpec& spec() const { return spec_; }
    const RigidBodyState& state() const { return state_; }
    /// Moves the car (a teleport, a rescue): replaces the state, puts the suspension at
    /// full droop (as place_car_on_surface and a new Car assume), and gives a vehicle
    /// model Vehicle::rolling_at(the new velocity along the car's heading): wheels spun to
    /// the road's speed without slip, in a gear for it. Restoring a snapshot is
    /// World::restore_state's (Car::restore, set_vehicle_state). Throws trackphys::Error if
    /// not finite. An orientation that is not a unit quaternion to within 8 ulps is
    /// normalised ((2, 0, 0, 0) is the identity); one no longer than 0.5 is refused.
    void set_state(const RigidBodyState& state);
    const CarInputs& inputs() const { return inputs_; }
    /// Sets the inputs, clamped to their ranges (throttle and steer -1..1, brake 0..1;
    /// infinities too). Throws trackphys::Error
    /// naming the input when one is NaN: a NaN is a bug upstream (a controller dividing by
    /// zero), not a command, and guessing a value for it would hide that bug.
    void set_inputs(const CarInputs& inputs);
    /// The front wheels' steer angle for the inputs (rad, > 0 to the left): inputs().steer
    /// times CarSpec::max_steer_angle. The rear wheels do not steer.
    double steer_angle() const { return inputs_.steer * spec_.max_steer_angle; }

    std::size_t ellipsoid_count() const { return shape_->body.size(); }
    /// Ellipsoid i in the body frame (relative to the centre of mass). Cars that share their
    /// ellipsoids (share_ellipsoids_with) return the same object. Every call taking an
    /// ellipsoid index throws trackphys::Error past ellipsoid_count().
    const Ellipsoid& body_ellipsoid(std::size_t i) const {
        return shape_->body[checked(i)].ellipsoid();
    }
    /// Ellipsoid i placed in the world by the current state (wheels moved up by their
    /// suspension travel).
    Ellipsoid world_ellipsoid(std::size_t i) const {
        return world_ellipsoid(i, glm::mat3_cast(state_.orientation));
    }
    /// The same with the orientation's matrix given, glm::mat3_cast(state().orientation), for
    /// a caller that places every ellipsoid of one state.
    Ellipsoid world_ellipsoid(std::size_t i, const glm::dmat3& orientation_matrix) const {
        return world_ellipsoid(i, PlacingRotation(state_.orientation, orientation_matrix));
    }
    /// The same with the orientation given as a PlacingRotation of state().orientation.
    Ellipsoid world_ellipsoid(std::size_t i, const PlacingRotation& orientation) const {
        Ellipsoid placed = shape_->body[checked(i)].ellipsoid();
        place_ellipsoid(i, orientation, placed);
        return placed;
    }
    /// Suspension compression of ellipsoid i from full droop (m; always 0 for the body).
    double suspension(std::size_t i) const { return suspension_[checked(i)]; }
    /// Suspension compression of every ellipsoid, in CarSpec order (m).
    std::span<const double> suspension() const { return suspension_; }
    /// The vehicle model (wheel spins, slips, gear, clutch, telemetry) of a car whose spec
    /// has a `vehicle`; null for the arcade car.
    const Vehicle* vehicle() const { return vehicle_ ? &*vehicle_ : nullptr; }
    /// The vehicle model, to set what is not state (Vehicle::set_road_grip).
    Vehicle* vehicle() { return vehicle_ ? &*vehicle_ : nullptr; }
    /// Replaces the vehicle model's state (restore). Throws trackphys::Error when the car
    /// has no vehicle model or Vehicle::set_state rejects the state.
    void set_vehicle_state(const VehicleState& state);
    /// Throws what set_vehicle_state() would throw for `state`, changing nothing.
    void check_vehicle_state(const VehicleState& state) const;
    /// Radius about the centre of mass of a sphere holding every ellipsoid, the wheels at any
    /// suspension travel (m).
    double bounding_radius() const { return bounding_radius_; }

    /// Speed of the centre of mass (m/s).
    double speed() const { return glm::length(state_.linear_velocity); }

    /// Applies an impulse J (N s, world) at world point p: v += J / m and
    /// omega += I_world^-1 ((p - x) x J), as a force J / h over a sub-step of h would.
    /// Contacts between cars push both cars this way, equal and opposite. Throws
    /// trackphys::Error, changing nothing, when J or p is not finite or the velocities would
    /// not be (a finite but absurd push is the World's reset policy's: see World).
    void apply_impulse(const glm::dvec3& impulse, const glm::dvec3& point);
    /// How much the velocity of the body point at world p changes along unit n per unit
    /// impulse along n there (1/kg): 1/m + n . ((I_world^-1 (r x n)) x r), r = p - x.
    double inverse_mass_along(const glm::dvec3& normal, const glm::dvec3& point) const;

  private:
    friend struct detail::CarAccess;

    struct Velocities {
        glm::dvec3 linear, angular;
    };
    // The velocities after an impulse J at world point p: apply_impulse's arithmetic.
    Velocities pushed(const glm::dvec3& impulse, const glm::dvec3& point) const;
    // apply_impulse without its check, for the contacts between cars in an update: a
    // non-finite push there is the reset policy's (an impossible state at the update's end),
    // not an error that would stop the World.
    void push(const glm::dvec3& impulse, const glm::dvec3& point);

    // i, when the car has an ellipsoid i.
    std::size_t checked(std::size_t i) const {
        if (i >= shape_->body.size()) throw_no_ellipsoid(i);
        return i;
    }
    [[noreturn]] void throw_no_ellipsoid(std::size_t i) const;

    /// One sub-step of h seconds from each ellipsoid's deepest contact (one per ellipsoid,
    /// in order; depth <= 0 for none): impulses for contacts the springs cannot hold, the
    /// contact and aerodynamic forces, the wheels' suspension travel, then integration
    /// under those forces and gravity.
    ///
    /// - Forces: each contact becomes a force at its point (body: spring, damper and
    ///   friction; wheels: also drive, brake and lateral grip), plus drag and downforce at
    ///   the centre of mass. Drive and brake act per axle like an open differential with
    ///   anti-lock brakes: each wheel of an axle gets the same share, at most
    ///   traction_limit of the grip of the axle's least loaded wheel, so a wheel in the air
    ///   never leaves its partner pulling the car sideways.
    /// - Deep contacts: an ellipsoid deeper than CarSpec::deep_contact_fraction of its
    ///   half-extent along the contact normal that still approaches the surface gets an
    ///   impulse removing the approaching velocity at its contact point (a plastic impact),
    ///   so a crash at 1000 km/h or a fall from 100 m stops at the surface instead of
    ///   tunnelling through it; ordinary driving never reaches that depth.
    /// - Suspension: each wheel moves along the body's up axis under its tyre's normal load
    ///   (see Suspension).
    /// - With a vehicle model (CarSpec::vehicle), the wheels' tangential forces come from
    ///   their spinning wheels and Magic Formula tyres instead (docs/vehicle.md), and the
    ///   anti-roll bars join the suspension.
    /// - Surfaces: `grip` holds each ellipsoid's Surface::grip (in order, finite and > 0), the
    ///   grip of the surface under its contact relative to the dry road; it scales the
    ///   friction of that contact (wheel and body; a vehicle model's tyre peaks, on top of
    ///   Vehicle::set_road_grip) and the traction limit of an arcade wheel. Empty: the dry
    ///   road under every ellipsoid (World passes it from WorldSettings::surfaces).
    void advance(std::span<const Contact> deepest, const glm::dvec3& gravity, double h,
                 std::span<const double> grip = {});

    /// Makes this car read its body-frame ellipsoids, and what its sub-steps read of each,
    /// from `other`'s copy when the two hold the same bits (cars of one spec): a field of
    /// many cars then keeps one copy warm in the cache rather than one per car. Nothing the
    /// car computes changes, and copies of the car share too. Returns whether they share.
    bool share_ellipsoids_with(const Car& other);
    /// The same written into `placed`, a copy of world_ellipsoid(i) of any state, with the
    /// orientation given, PlacingRotation(state().orientation): a car places all its
    /// ellipsoids of one state with one rotation, each into its own slot
    /// (Ellipsoid::place_copy).
    void place_ellipsoid(std::size_t i, const PlacingRotation& orientation,
                         Ellipsoid& placed) const {
        shape_->body[i].place_copy(placed, orientation, state_.position + lifted(suspension_[i]));
    }
    /// Replaces the suspension compressions (restore, reset). Throws trackphys::Error unless
    /// there is one per ellipsoid, each in [0, CarSpec::suspension.travel] (0 for the body).
    void set_suspension(std::span<const double> travel);
    /// Replaces state, inputs and suspension with exactly these bits (no renormalisation, no
    /// clamping), as World::restore_state needs for bit-identical results. Throws
    /// trackphys::Error, changing nothing, when set_state or set_suspension would reject
    /// them, the orientation is off unit length by more than 1e-6, or an input is NaN or out
    /// of its range.
    void restore(const RigidBodyState& state, const CarInputs& inputs,
                 std::span<const double> suspension);
    /// Throws what restore() would throw for these, changing nothing: a caller restoring
    /// several cars checks them all first, then restores each in place.
    void check_restore(const RigidBodyState& state, const CarInputs& inputs,
                       std::span<const double> suspension) const;
    /// Throws what set_suspension() would throw for `travel`, changing nothing.
    void check_suspension(std::span<const double> travel) const;

    /// state().orientation * (0, travel, 0), a wheel's suspension lift in the world, as glm
    /// rotates it (v + 2 (w (q x v) + q x (q x v)), q the vector part) but without the
    /// products by v's zero components, which change at most the sign of a zero: a fifth
    /// of a wheel's placing.
    glm::dvec3 lifted(double travel) const {
        const glm::dquat& q = state_.orientation;
        const double a = travel * q.z;  // q x v = (-a, 0, b)
        const double b = q.x * travel;
        const double cross_y = q.z * -a - b * q.x;  // y of q x (q x v)
        return {(-a * q.w + q.y * b) * 2.0, travel + cross_y * 2.0, (b * q.w + a * q.y) * 2.0};
    }
    /// A wheel's axle, which sets its heading, grip and share of drive and brake; also the
    /// index of per-axle arrays.
    enum class Axle : int { front = 0, rear = 1 };
    static Axle axle_of(EllipsoidRole wheel) {
        return wheel == EllipsoidRole::front_wheel ? Axle::front : Axle::rear;
    }
    Axle axle_of(std::size_t wheel) const { return axle_of(shape_->parts[wheel].role); }
    /// What a sub-step reads of an ellipsoid besides its contact, in one small block: not
    /// from the spec's CarEllipsoids (88 bytes each) and the body Ellipsoids (176).
    struct Part {
        EllipsoidRole role;
        /// Only a contact deeper than this is deep (resolve_deep_contacts): the smallest
        /// radius's share, less an ulp-sized margin for its rounding.
        double deep_contact_depth;
    };
    /// What the spec fixes of the ellipsoids, never changed after construction: the body
    /// frame's Ellipsoids (with what placing finds of them) that placing reads every
    /// sub-step, and the Parts.
    struct Shape {
        std::vector<detail::BodyEllipsoid> body;  // in CarSpec order
        std::vector<Part> parts;                  // the same order
        /// One past the last wheel: every ellipsoid from here on is body, which the loops
        /// over wheels need not visit (the presets list their wheels first).
        std::size_t wheel_end = 0;
        bool same_bits(const Shape& other) const;
    };
    /// A wheel's tyre this sub-step (measure_wheel_loads): the velocity of its contact point
    /// and the normal force measured at it (N). A body ellipsoid's is not set.
    /// Scratch of one sub-step, on advance's stack: a car's own copy would be written cold
    /// at each of its updates in a big field.
    struct WheelLoad {
        glm::dvec3 velocity;
        double load;
    };
    using WheelLoads = std::array<WheelLoad, CarSpec::max_ellipsoids>;
    /// The load of each axle's least loaded wheel (N; infinity for an axle with none),
    /// indexed by Axle: it bounds the axle's drive and brake.
    using AxleLoads = std::array<double, 2>;

    void resolve_deep_contacts(std::span<const Contact> deepest);
    /// The tyre's normal force of each wheel and the velocity of its contact point, into
    /// wheel_loads' first deepest.size(); returns each axle's least load.
    AxleLoads measure_wheel_loads(std::span<const Contact> deepest, WheelLoads& wheel_loads) const;
    /// axes: detail::BodyAxes(state().orientation), this sub-step's (the forward axis is the rear
    /// wheels' heading and the downforce's speed).
    /// grip: advance's, empty for 1 everywhere.
    Wrench contact_wrench(std::span<const Contact> deepest, std::span<const double> grip,
                          const WheelLoads& wheel_loads, const AxleLoads& least_loads,
                          const detail::BodyAxes& axes) const;
    /// contact_wrench for a car with a vehicle model; advances its wheels by h.
    Wrench vehicle_wrench(std::span<const Contact> deepest, std::span<const double> grip,
                          const WheelLoads& wheel_loads, const detail::BodyAxes& axes, double h);
    /// `material` with its friction scaled by a surface's grip (times 1 leaves its bits).
    static ContactMaterial on_surface(ContactMaterial material, double grip) {
        material.friction *= grip;
        return material;
    }
    /// The world direction the wheels of an axle roll in (the front ones steered); forward:
    /// the body's forward axis.
    glm::dvec3 wheel_heading(Axle axle, const glm::dvec3& forward) const {
        return axle == Axle::front ? state_.orientation * steered_heading_ : forward;
    }
    /// up: the body's up axis.
    void update_suspension(std::span<const Contact> deepest, const WheelLoads& wheel_loads,
                           const glm::dvec3& up, double h);
    // wheel_command, drive_available and wheel_material are defined inline in car.cpp: call
    // them only from there (another file's call would not link).
    /// The command of each wheel of an axle rolling along heading on material
    /// (wheel_material); available: drive_available(), the drive force at this speed (N,
    /// all wheels).
    WheelCommand wheel_command(Axle axle, const glm::dvec3& heading,
                               const ContactMaterial& material, double axle_normal_force,
                               double available) const;
    /// speed_now: speed().
    double drive_available(double speed_now) const;
    /// The drive force backwards at this speed (N, all wheels, >= 0): drive_available()
    /// once the car is nearly stopped or rolling backwards, fading linearly to none at
    /// CarSpec::max_reverse_speed; none while it rolls forwards. forward_speed: the
    /// velocity along the body's forward axis (m/s).
    double reverse_available(double speed_now, double forward_speed) const;
    /// Sets inputs_ (already in range) and the steered heading that follows from them.
    void take_inputs(const CarInputs& inputs);
    /// The contact material of an axle's wheels (rear tyres with their extra grip).
    ContactMaterial wheel_material(Axle axle) const;
    /// speed_now: speed(); forward and down: the body's axes. Defined here, as the sub-step's
    /// other small laws are, so that both wrenches compile it in rather than call it.
    void add_aero_force(Wrench& wrench, double speed_now, const glm::dvec3& forward,
                        const glm::dvec3& down) const {
        const glm::dvec3& v = state_.linear_velocity;
        const double dynamic_pressure = 0.5 * spec_.air_density * glm::dot(v, v);
        if (speed_now > 0.0) wrench.force -= v * (dynamic_pressure * spec_.drag_area / speed_now);
        // Downforce pushes along the body's down axis, in proportion to the forward speed.
        const double forward_speed = glm::dot(v, forward);
        wrench.force +=
            down * (0.5 * spec_.air_density * forward_speed * forward_speed * spec_.downforce_area);
    }

    CarSpec spec_;
    RigidBodyState state_;
    CarInputs inputs_;
    glm::dvec3 steered_heading_{0.0, 0.0, 1.0};  // front wheels', body frame, for inputs_.steer
    std::shared_ptr<const Shape> shape_;         // shared by the cars of one spec in a World
    std::vector<double> suspension_;
    std::optional<Vehicle> vehicle_;
    double bounding_radius_ = 0.0;
    int front_wheels_ = 0;
    int wheels_ = 0;
};

}  // namespace trackphys
