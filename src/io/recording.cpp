#include "trackphys/io/recording.hpp"

#include <cinttypes>
#include <cstdio>
#include <initializer_list>
#include <system_error>

#include "car_spec_json_detail.hpp"
#include "trackphys/error.hpp"

namespace trackphys {
namespace {

// %.17g keeps every bit of a double, so a replay sees exactly the simulated values.
void put(std::ofstream& out, double x) {
    char text[32];
    std::snprintf(text, sizeof text, "%.17g", x);
    out << text;
}

void put_list(std::ofstream& out, std::span<const double> values) {
    out << '[';
    for (std::size_t i = 0; i < values.size(); ++i) {
        if (i > 0) out << ',';
        put(out, values[i]);
    }
    out << ']';
}

void put_list(std::ofstream& out, std::initializer_list<double> values) {
    put_list(out, std::span<const double>(values.begin(), values.size()));
}

void put(std::ofstream& out, const glm::dvec3& v) { put_list(out, {v.x, v.y, v.z}); }

}  // namespace

RecordingWriter::RecordingWriter(const std::filesystem::path& path, const RecordingHeader& header)
    : path_(path), temporary_(path.string() + ".partial") {
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
    if (update_us) out_ << ",\"us\":", put(out_, *update_us);
    out_ << ",\"cars\":[";
    first_car_ = true;
}

void RecordingWriter::add_car(const RecordedCar& car) {
    out_ << (first_car_ ? "" : ",") << "{\"p\":";
    first_car_ = false;
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
    out_ << "]}";
}

void RecordingWriter::end_frame() { out_ << "]}\n"; }

void RecordingWriter::finish() {
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
