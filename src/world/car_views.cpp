#include "world/car_views.hpp"

#include <limits>
#include <string>

#include <glm/gtc/quaternion.hpp>
#include <glm/mat3x3.hpp>

#include "trackphys/error.hpp"
#include "trackphys/vehicle/vehicle.hpp"

namespace trackphys::detail {
namespace {

// The wheel's frame: the body's, steered about its up axis (+Y), spun about the axle (+X:
// a positive angle turns +Y towards +Z, the way a wheel rolling forward turns).
glm::dquat wheel_orientation(const glm::dquat& body, double steer_angle, double spin_angle) {
    return body * glm::angleAxis(steer_angle, glm::dvec3(0.0, 1.0, 0.0)) *
           glm::angleAxis(spin_angle, glm::dvec3(1.0, 0.0, 0.0));
}

template <typename T>
T lerp(const T& older, const T& newer, double alpha) {
    return older + (newer - older) * alpha;
}

}  // namespace

CarView sized_view(const Car& car) {
    CarView view;
    for (std::size_t i = 0; i < car.ellipsoid_count(); ++i)
        if (car.spec().ellipsoids[i].role != EllipsoidRole::body) view.wheels.push_back({i});
    take_view(car, view, 0.0, view);
    return view;
}

void take_view(const Car& car, const CarView& last, double dt, CarView& out) {
    const RigidBodyState& state = car.state();
    const Vehicle* vehicle = car.vehicle();
    out.pose = {state.position, state.orientation};
    out.linear_velocity = state.linear_velocity;
    out.angular_velocity = state.angular_velocity;
    out.engine_rpm = vehicle ? vehicle->engine_rpm() : 0.0;
    out.gear = vehicle ? vehicle->state().gear : 0;
    const glm::dmat3 rotation = glm::mat3_cast(state.orientation);
    for (std::size_t w = 0; w < out.wheels.size(); ++w) {
        WheelView& wheel = out.wheels[w];
        const std::size_t i = wheel.ellipsoid;
        const bool front = car.spec().ellipsoids[i].role == EllipsoidRole::front_wheel;
        const double last_spin = last.wheels[w].spin;  // read before out overwrites it
        wheel.position = car.world_ellipsoid(i, rotation).center();
        wheel.suspension = car.suspension(i);
        wheel.steer_angle = front ? car.steer_angle() : 0.0;
        wheel.spin = vehicle ? vehicle->state().wheels[vehicle->wheel_slot(i)].spin : 0.0;
        wheel.spin_angle = last.wheels[w].spin_angle + 0.5 * (last_spin + wheel.spin) * dt;
        wheel.orientation =
            wheel_orientation(state.orientation, wheel.steer_angle, wheel.spin_angle);
    }
}

CarPose interpolate(const CarPose& older, const CarPose& newer, double alpha) {
    if (alpha == 0.0) return older;
    if (alpha == 1.0) return newer;
    return {lerp(older.position, newer.position, alpha),
            glm::slerp(older.orientation, newer.orientation, alpha)};
}

void interpolate(const CarView& older, const CarView& newer, double alpha, CarView& out) {
    if (alpha == 0.0 || alpha == 1.0) {
        out = alpha == 0.0 ? older : newer;
        return;
    }
    out.pose = interpolate(older.pose, newer.pose, alpha);
    out.linear_velocity = lerp(older.linear_velocity, newer.linear_velocity, alpha);
    out.angular_velocity = lerp(older.angular_velocity, newer.angular_velocity, alpha);
    out.engine_rpm = lerp(older.engine_rpm, newer.engine_rpm, alpha);
    out.gear = newer.gear;
    out.wheels.resize(newer.wheels.size());
    for (std::size_t w = 0; w < out.wheels.size(); ++w) {
        const WheelView& a = older.wheels[w];
        const WheelView& b = newer.wheels[w];
        WheelView& wheel = out.wheels[w];
        wheel.ellipsoid = b.ellipsoid;
        wheel.position = lerp(a.position, b.position, alpha);
        wheel.suspension = lerp(a.suspension, b.suspension, alpha);
        wheel.steer_angle = lerp(a.steer_angle, b.steer_angle, alpha);
        wheel.spin = lerp(a.spin, b.spin, alpha);
        wheel.spin_angle = lerp(a.spin_angle, b.spin_angle, alpha);
        wheel.orientation =
            wheel_orientation(out.pose.orientation, wheel.steer_angle, wheel.spin_angle);
    }
}

}  // namespace trackphys::detail

namespace trackphys {
namespace {

// Whether the view holds car's wheels, in order.
bool holds_wheels_of(const CarView& view, const Car& car) {
    std::size_t w = 0;
    for (std::size_t i = 0; i < car.ellipsoid_count(); ++i) {
        if (car.spec().ellipsoids[i].role == EllipsoidRole::body) continue;
        if (w >= view.wheels.size() || view.wheels[w].ellipsoid != i) return false;
        ++w;
    }
    return w == view.wheels.size();
}

}  // namespace

void update_car_view(const Car& car, double dt, CarView& view) {
    if (!(dt >= 0.0 && dt <= std::numeric_limits<double>::max()))
        throw Error("update_car_view: dt must be finite and >= 0, got " + exact_text(dt));
    if (!holds_wheels_of(view, car)) {
        view = detail::sized_view(car);
        return;
    }
    detail::take_view(car, view, dt, view);
}

void interpolate_car_view(const CarView& older, const CarView& newer, double alpha, CarView& out) {
    if (!(alpha >= 0.0 && alpha <= 1.0))
        throw Error("interpolate_car_view: alpha must be in [0, 1], got " + exact_text(alpha));
    bool same_wheels = older.wheels.size() == newer.wheels.size();
    for (std::size_t w = 0; same_wheels && w < older.wheels.size(); ++w)
        same_wheels = older.wheels[w].ellipsoid == newer.wheels[w].ellipsoid;
    if (!same_wheels)
        throw Error("interpolate_car_view: the two views hold other wheels (views of two cars?)");
    detail::interpolate(older, newer, alpha, out);
}

}  // namespace trackphys
