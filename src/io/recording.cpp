#include "trackphys/io/recording.hpp"

#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <initializer_list>
#include <numbers>
#include <system_error>

#include "car_spec_json_detail.hpp"
#include "trackphys/error.hpp"

namespace trackphys {
namespace {

// How a number is written. The state (poses, speeds, contacts) keeps every bit of its
// doubles, so a replay sees exactly the simulated values; telemetry is for reading off a
// display or a chart, where 9 significant digits are more than any channel resolves (as
// in --telemetry's CSV).
constexpr const char* kExact = "%.17g";
constexpr const char* kTelemetry = "%.9g";
// Microseconds to the steady clock's nanosecond: more digits would be the division's noise.
constexpr const char* kNanoseconds = "%.3f";

void put(std::ofstream& out, double x, const char* format = kExact) {
    char text[32];
    std::snprintf(text, sizeof text, format, x);
    out << text;
}

void put_list(std::ofstream& out, std::span<const double> values, const char* format = kExact) {
    out << '[';
    for (std::size_t i = 0; i < values.size(); ++i) {
        if (i > 0) out << ',';
        put(out, values[i], format);
    }
    out << ']';
}

void put_list(std::ofstream& out, std::initializer_list<double> values,
              const char* format = kExact) {
    put_list(out, std::span<const double>(values.begin(), values.size()), format);
}

void put(std::ofstream& out, const glm::dvec3& v) { put_list(out, {v.x, v.y, v.z}); }

void put_vehicle(std::ofstream& out, const RecordedVehicle& vehicle) {
    out << ",\"vehicle\":{\"rpm\":";
    put(out, vehicle.engine_rpm, kTelemetry);
    out << ",\"gear\":" << vehicle.gear << ",\"wheels\":[";
    constexpr double kDegrees = 180.0 / std::numbers::pi;
    for (std::size_t i = 0; i < vehicle.wheels.size(); ++i) {
        const WheelTelemetry& w = vehicle.wheels[i];
        out << (i > 0 ? "," : "");
        put_list(out, {w.slip_ratio, std::atan(w.lateral_slip) * kDegrees, w.load, w.spin},
                 kTelemetry);
    }
    out << "]}";
}

}  // namespace

RecordingWriter::RecordingWriter(const std::filesystem::path& path, const RecordingHeader& header)
    : path_(path), temporary_(path.string() + ".partial") {
    for (const std::vector<CarEllipsoid>& car : header.car_ellipsoids)
        ellipsoids_.push_back(car.size());
    out_.open(temporary_, std::ios::binary | std::ios::trunc);
    if (!out_) throw Error("cannot open '" + temporary_.string() + "' to write the recording");
    json_io::Json line = {{"format", "trackphys-recording"},
                          {"version", 2},
                          {"dt", header.dt},
                          {"cars", header.car_ellipsoids.size()},
                          {"scene", header.scene}};
    if (!header.track_mesh.empty()) line["track"] = {{"mesh", header.track_mesh.generic_string()}};
    line["car_ellipsoids"] = json_io::Json::array();
    for (const std::vector<CarEllipsoid>& car : header.car_ellipsoids)
        line["car_ellipsoids"].push_back(json_io::car_ellipsoids_to_json(car));
    // Invalid UTF-8 in a scene description (a mesh file's name) is replaced, not thrown.
    out_ << line.dump(-1, ' ', false, json_io::Json::error_handler_t::replace) << '\n';
}

RecordingWriter::~RecordingWriter() {
    if (finished_) return;
    out_.close();
    std::error_code ignored;
    std::filesystem::remove(temporary_, ignored);
}

void RecordingWriter::begin_frame(double t, std::uint64_t state_hash,
                                  std::optional<double> update_us) {
    char hash[17];
    std::snprintf(hash, sizeof hash, "%016" PRIx64, state_hash);
    out_ << "{\"t\":";
    put(out_, t);
    out_ << ",\"hash\":\"" << hash << '"';
    if (update_us) out_ << ",\"us\":", put(out_, *update_us, kNanoseconds);
    out_ << ",\"cars\":[";
    line_cars_ = 0;
}

void RecordingWriter::add_car(const RecordedCar& car) {
    const std::size_t k = line_cars_;
    const auto refuse = [&](const std::string& why) {
        unfinished_line_ = true;
        throw Error("recording '" + path_.string() + "': " + why);
    };
    if (k >= ellipsoids_.size())
        refuse("car " + std::to_string(k) + " is past the header's " +
               std::to_string(ellipsoids_.size()));
    // The viewer reads one suspension per ellipsoid; contacts are by ellipsoid, or none.
    if (car.suspension.size() != ellipsoids_[k] ||
        (!car.contacts.empty() && car.contacts.size() != ellipsoids_[k]))
        refuse("car " + std::to_string(k) + " has " + std::to_string(car.suspension.size()) +
               " ellipsoids' suspension and " + std::to_string(car.contacts.size()) +
               " contacts, its header " + std::to_string(ellipsoids_[k]) + " ellipsoids");
    out_ << (k == 0 ? "" : ",") << "{\"p\":";
    ++line_cars_;
    put(out_, car.position);
    out_ << ",\"q\":";
    put_list(out_, {car.orientation.w, car.orientation.x, car.orientation.y, car.orientation.z});
    out_ << ",\"v\":";
    put(out_, car.speed);
    out_ << ",\"s\":";
    put_list(out_, car.suspension);
    if (car.inputs) {
        out_ << ",\"in\":";
        put_list(out_, {car.inputs->throttle, car.inputs->brake, car.inputs->steer});
    }
    if (car.laps) out_ << ",\"lap\":" << *car.laps;
    out_ << ",\"contacts\":[";
    bool first = true;
    for (std::size_t i = 0; i < car.contacts.size(); ++i) {
        const Contact& c = car.contacts[i];
        if (!(c.depth > 0.0)) continue;
        out_ << (first ? "" : ",");
        first = false;
        put_list(out_, {c.point.x, c.point.y, c.point.z, c.normal.x, c.normal.y, c.normal.z,
                        c.depth, static_cast<double>(i)});
    }
    out_ << ']';
    if (car.vehicle) put_vehicle(out_, *car.vehicle);
    out_ << '}';
}

void RecordingWriter::end_frame(std::span<const CarPairContact> car_contacts) {
    const auto refuse = [&](const std::string& why) {
        unfinished_line_ = true;
        throw Error("recording '" + path_.string() + "': " + why);
    };
    if (line_cars_ != ellipsoids_.size())
        refuse("a line of " + std::to_string(line_cars_) + " cars, the header's " +
               std::to_string(ellipsoids_.size()));
    // The viewer draws a car contact on the two cars' ellipsoids it names.
    for (const CarPairContact& c : car_contacts)
        if (!(c.car_a < c.car_b && c.car_b < ellipsoids_.size() &&
              c.ellipsoid_a < ellipsoids_[c.car_a] && c.ellipsoid_b < ellipsoids_[c.car_b]))
            refuse("a contact between car " + std::to_string(c.car_a) + "'s ellipsoid " +
                   std::to_string(c.ellipsoid_a) + " and car " + std::to_string(c.car_b) +
                   "'s ellipsoid " + std::to_string(c.ellipsoid_b) +
                   ": not two of the header's cars, the lower first, and their ellipsoids");
    out_ << ']';
    bool first = true;
    for (const CarPairContact& c : car_contacts) {
        if (!(c.contact.depth > 0.0)) continue;
        out_ << (first ? ",\"car_contacts\":[" : ",");
        first = false;
        const Contact& k = c.contact;
        put_list(out_,
                 {static_cast<double>(c.car_a), static_cast<double>(c.car_b),
                  static_cast<double>(c.ellipsoid_a), static_cast<double>(c.ellipsoid_b), k.point.x,
                  k.point.y, k.point.z, k.normal.x, k.normal.y, k.normal.z, k.depth});
    }
    out_ << (first ? "}\n" : "]}\n");
}

void RecordingWriter::finish() {
    if (unfinished_line_)
        throw Error("recording '" + path_.string() +
                    "': not put in place, an earlier error left a line unfinished");
    out_.flush();
    if (!out_) throw Error("cannot write the recording '" + temporary_.string() + "'");
    out_.close();
    std::error_code error;
    std::filesystem::rename(temporary_, path_, error);
    if (error)
        throw Error("cannot move the recording into place at '" + path_.string() +
                    "': " + error.message());
    finished_ = true;
}

}  // namespace trackphys
