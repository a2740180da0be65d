#include "trackphys/world/autopilot.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <sstream>
#include <string>
#include <utility>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

#include "trackphys/error.hpp"

namespace trackphys {
namespace {

constexpr double g = 9.81;

// Yaw rate beyond the arc's (rad/s) at which a sliding car is fully off the throttle.
constexpr double kOversteerYawError = 0.3;

// The fastest steady speed through a banked turn of radius r and bank theta with friction
// mu and aerodynamic downforce coefficient k = rho C_l A / 2 per unit mass (1/m). In the
// road plane the tyres must supply m v^2/r cos(theta) - m g sin(theta), at most mu times
// the normal load m g cos(theta) + m v^2/r sin(theta) + m k v^2, so
//   v^2 (cos(theta)/r - mu sin(theta)/r - mu k) <= g (sin(theta) + mu cos(theta)).
// A non-positive bracket means grip grows faster than the demand: no limit.
double cornering_speed_limit(double radius, double bank, double mu, double k) {
    const double demand = std::cos(bank) / radius - mu * std::sin(bank) / radius - mu * k;
    if (demand <= 0.0) return std::numeric_limits<double>::infinity();
    return std::sqrt(g * (std::sin(bank) + mu * std::cos(bank)) / demand);
}

// Curvature of the road over a crest (1/m, > 0 where the road falls away from the car):
// minus the rate at which the tangent turns towards the road's up, from the neighbours.
double vertical_curvature(const std::vector<CenterlineSample>& c, std::size_t i, double length) {
    const std::size_t n = c.size();
    const CenterlineSample& before = c[(i + n - 1) % n];
    const CenterlineSample& after = c[(i + 1) % n];
    double span = after.distance - before.distance;
    if (span <= 0.0) span += length;
    return -glm::dot(after.tangent - before.tangent, c[i].up) / span;
}

// Over a crest of curvature kappa the road's push may not fall to zero: the car needs
// v^2 kappa <= g + k v^2 (gravity and downforce hold it down), with a third in reserve.
double crest_speed_limit(double kappa, double k) {
    const double demand = kappa - k;
    if (demand <= 0.0) return std::numeric_limits<double>::infinity();
    return std::sqrt(2.0 / 3.0 * g / demand);
}

}  // namespace

std::string AutopilotSettings::validate() const {
    std::ostringstream why;
    const auto check = [&](const char* name, double value, bool zero_allowed) {
        if (why.tellp() == 0 &&
            !(std::isfinite(value) && (value > 0.0 || (zero_allowed && value == 0.0))))
            why << "AutopilotSettings." << name << " must be finite and "
                << (zero_allowed ? ">= 0" : "> 0") << ", got " << exact_text(value);
    };
    check("target_speed", target_speed, false);
    check("grip_use", grip_use, false);
    check("braking", braking, false);
    check("braking_grip_use", braking_grip_use, false);
    check("lookahead_min", lookahead_min, true);
    check("lookahead_time", lookahead_time, true);
    check("yaw_damping", yaw_damping, true);
    return why.str();
}

Autopilot::Autopilot(const Track& track, const CarSpec& car, AutopilotSettings settings)
    : Autopilot(std::make_shared<const std::vector<CenterlineSample>>(track.centerline),
                track.length_m, car, settings) {}

Autopilot::Autopilot(SharedCenterline shared, double length_m, const CarSpec& car,
                     AutopilotSettings settings)
    : centerline_(std::move(shared)), length_(length_m), settings_(settings) {
    if (!centerline_ || centerline_->size() < 3)
        throw Error("Autopilot: the track has no centreline");
    if (!(std::isfinite(length_) && length_ > 0.0))
        throw Error("Autopilot: the track's length must be finite and > 0");
    const std::vector<CenterlineSample>& line = *centerline_;
    if (std::string why = settings_.validate(); !why.empty()) throw Error("Autopilot: " + why);

    double front = -std::numeric_limits<double>::infinity();
    double rear = std::numeric_limits<double>::infinity();
    for (const CarEllipsoid& e : car.ellipsoids) {
        if (e.role == EllipsoidRole::front_wheel) front = std::max(front, e.center.z);
        if (e.role == EllipsoidRole::rear_wheel) rear = std::min(rear, e.center.z);
    }
    wheelbase_ = std::isfinite(front - rear) && front > rear ? front - rear : 2.5;
    max_steer_angle_ = car.max_steer_angle;
    const std::size_t samples = line.size();
    for (std::size_t i = 0; i < samples; ++i)
        max_sample_gap_ = std::max(
            max_sample_gap_, glm::distance(line[i].position, line[(i + 1) % samples].position));
    // Rounded up, so that no bound built on it promises more than the chords give.
    max_sample_gap_ = max_sample_gap_ * (1.0 + 1e-12) + 1e-12;

    // Speed profile: each sample's cornering limit (the bank helps only when it leans into
    // the turn) and crest limit, then a backward pass so the car can brake down to every
    // limit in time.
    // A car with a vehicle model plans with its tyres' friction at the top of their load
    // range (banked turns load them heavily), the lower axle's.
    const double mu = settings_.grip_use *
                      (car.vehicle ? std::min(car.vehicle->front_tyre.lateral.lowest_friction(),
                                              car.vehicle->rear_tyre.lateral.lowest_friction())
                                   : car.wheel_contact.friction);
    const double braking =
        car.vehicle ? settings_.braking_grip_use * g *
                          std::min(car.vehicle->front_tyre.longitudinal.lowest_friction(),
                                   car.vehicle->rear_tyre.longitudinal.lowest_friction())
                    : settings_.braking;
    const double k = 0.5 * car.air_density * car.downforce_area / car.mass.mass;
    const std::size_t n = line.size();
    std::vector<double> crest_curvature(n);
    for (std::size_t i = 0; i < n; ++i) crest_curvature[i] = vertical_curvature(line, i, length_);
    // Over a crest of curvature kappa the road pushes v^2 kappa less per unit mass, like
    // negative downforce. A car with a vehicle model plans its turns and braking with that
    // load: braking or turning over a crest at the flat road's limit slides its tyres
    // past their peaks. A dip's extra load is not counted on: the wheels skip over the
    // facet kinks at the bottom. (The arcade car's plan stays as it was: its laps are
    // pinned by hash, and its grip saturates without a peak.)
    const auto downforce = [&](std::size_t i) {
        return car.vehicle ? k - std::max(crest_curvature[i], 0.0) : k;
    };
    planned_speed_.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        const CenterlineSample& s = line[i];
        const double radius = 1.0 / std::max(std::abs(s.curvature), 1e-9);
        const double bank_into_turn = s.curvature >= 0.0 ? s.bank : -s.bank;
        planned_speed_[i] =
            std::min({settings_.target_speed,
                      cornering_speed_limit(radius, bank_into_turn, mu, downforce(i)),
                      crest_speed_limit(crest_curvature[i], k)});
    }
    // Two laps backwards so the limit carries across the start line.
    for (std::size_t step = 0; step < 2 * n; ++step) {
        const std::size_t i = (2 * n - 1 - step) % n;
        const std::size_t next = (i + 1) % n;
        double gap = line[next].distance - line[i].distance;
        if (gap <= 0.0) gap += length_;
        const double v_next = planned_speed_[next];
        // Never < 0: a crest may leave no grip to brake with, never a need to speed up.
        const double decel = std::max(0.0, braking + downforce(next) * v_next * v_next * mu);
        planned_speed_[i] =
            std::min(planned_speed_[i], std::sqrt(v_next * v_next + 2.0 * decel * gap));
    }
}

std::size_t Autopilot::find_nearest(const glm::dvec3& position) const {
    const std::vector<CenterlineSample>& line = centerline();
    const std::size_t n = line.size();
    auto distance2 = [&](std::size_t i) {
        const glm::dvec3 d = line[i].position - position;
        return glm::dot(d, d);
    };
    if (!located_) {  // first call: search everything
        std::size_t best = 0;
        double best_distance2 = distance2(0);
        for (std::size_t i = 1; i < n; ++i)
            if (const double d2 = distance2(i); d2 < best_distance2) best = i, best_distance2 = d2;
        return best;
    }
    // Afterwards the car is near where it was: search a window around the last sample,
    // outwards, the sample ahead before the one behind at the same step (a tie keeps the
    // first found). A sample at distance d from the car puts the next m samples on its
    // side at least d - m max_sample_gap_ away, so those that cannot come nearer than the
    // best so far are never read: the window's samples would push a big field's lines out
    // of the cache between two updates. The margin covers the roundings of the distances
    // compared.
    constexpr std::size_t window = 400;
    const double margin =
        1e-6 + 1e-9 * (std::abs(position.x) + std::abs(position.y) + std::abs(position.z));
    std::size_t best = nearest_;
    double best_distance2 = distance2(best);
    const auto steps_out_of_reach = [&](double d2) -> std::size_t {
        const double reach = (std::sqrt(d2) - std::sqrt(best_distance2) - margin) / max_sample_gap_;
        return reach > 1.0 ? static_cast<std::size_t>(std::ceil(std::min(reach, 1.0 * window))) - 1
                           : 0;
    };
    std::size_t ahead_step = 1;
    std::size_t behind_step = 1;
    while (ahead_step <= window || behind_step <= window) {
        const bool ahead = ahead_step <= behind_step;
        std::size_t& step = ahead ? ahead_step : behind_step;
        const std::size_t i = ahead ? (nearest_ + step) % n : (nearest_ + n - step % n) % n;
        const double d2 = distance2(i);
        if (d2 < best_distance2) best = i, best_distance2 = d2;
        step += 1 + steps_out_of_reach(d2);
    }
    return best;
}

std::size_t Autopilot::sample_ahead(std::size_t from, double distance) const {
    const std::vector<CenterlineSample>& line = centerline();
    const std::size_t n = line.size();
    std::size_t i = from;
    double travelled = 0.0;
    while (travelled < distance) {
        const std::size_t next = (i + 1) % n;
        double gap = line[next].distance - line[i].distance;
        if (gap <= 0.0) gap += length_;
        travelled += gap;
        i = next;
        if (i == from) break;
    }
    return i;
}

void Autopilot::locate(const Car& car) {
    const std::size_t previous = nearest_;
    nearest_ = find_nearest(car.state().position);
    // Crossing the start line forwards: the index wraps from the last samples to the first.
    const std::size_t n = centerline().size();
    if (located_ && previous > nearest_ && previous - nearest_ > n / 2) ++laps_;
    if (located_ && nearest_ > previous && nearest_ - previous > n / 2 && laps_ > 0) --laps_;
    located_ = true;
}

void Autopilot::check_progress(const AutopilotProgress& progress) const {
    if (progress.nearest_sample >= centerline().size())
        throw Error("Autopilot progress: sample " + std::to_string(progress.nearest_sample) +
                    " is beyond the centreline's " + std::to_string(centerline().size()) +
                    " samples");
    if (progress.laps < 0) throw Error("Autopilot progress: laps must be >= 0");
}

void Autopilot::set_progress(const AutopilotProgress& progress) {
    check_progress(progress);
    nearest_ = progress.nearest_sample;
    laps_ = progress.laps;
    located_ = progress.located;
}

CarInputs Autopilot::drive(const Car& car) {
    locate(car);
    const RigidBodyState& state = car.state();
    const double speed = car.speed();
    CarInputs inputs;

    // Speed: aim for the plan a little ahead (the car needs time to react).
    const double target =
        std::min(planned_speed_[sample_ahead(nearest_, speed * 0.3 + 2.0)], speed_limit_);
    const double error = target - speed;
    inputs.throttle = std::clamp(0.5 * error, 0.0, 1.0);
    inputs.brake = std::clamp(-0.3 * error, 0.0, 1.0);

    // Pure pursuit: steer onto the arc through the look-ahead point.
    const double lookahead = settings_.lookahead_min + settings_.lookahead_time * speed;
    const CenterlineSample& ahead = centerline()[sample_ahead(nearest_, lookahead)];
    const glm::dvec3 goal = ahead.position + ahead.left * lane_offset_;
    const glm::dvec3 local = glm::conjugate(state.orientation) * (goal - state.position);
    const double planar2 = local.x * local.x + local.z * local.z;
    const double curvature = planar2 > 1e-6 ? 2.0 * local.x / planar2 : 0.0;
    // Yaw damping, like a stability control: steer against the difference between the
    // yaw rate the arc asks for (v kappa) and the car's, which catches a sliding or
    // spinning car long before the look-ahead point would.
    const glm::dvec3 up = state.orientation * glm::dvec3(0.0, 1.0, 0.0);
    const double yaw_rate = glm::dot(state.angular_velocity, up);
    const double yaw_error = speed * curvature - yaw_rate;
    const double angle = std::atan(curvature * wheelbase_) +
                         settings_.yaw_damping * wheelbase_ * yaw_error / std::max(speed, 5.0);
    // A car that cannot steer (max_steer_angle 0, which its spec allows) is held straight.
    inputs.steer = max_steer_angle_ > 0.0 ? std::clamp(angle / max_steer_angle_, -1.0, 1.0) : 0.0;
    // A car with a vehicle model whose rear steps out (it yaws faster than the arc asks,
    // the same way) comes off the throttle, as a driver does: the drive torque takes the
    // rear tyres' lateral grip, and a rear-driven car would spin out of the turn.
    if (car.vehicle() && yaw_rate * yaw_error < 0.0)
        inputs.throttle *= std::clamp(1.0 - std::abs(yaw_error) / kOversteerYawError, 0.0, 1.0);
    return inputs;
}

}  // namespace trackphys
