#include "telemetry_csv.hpp"

#include <cmath>
#include <cstdio>
#include <vector>

#include "trackphys/error.hpp"

namespace trackphys::cli {
namespace {

// The wheels' channel prefixes in CarSpec order: front/rear and left/right (+X is left).
std::vector<std::string> wheel_names(const CarSpec& spec) {
    std::vector<std::string> names;
    for (const CarEllipsoid& e : spec.ellipsoids) {
        if (e.role == EllipsoidRole::body) continue;
        names.push_back(std::string(e.role == EllipsoidRole::front_wheel ? "f" : "r") +
                        (e.center.x > 0.0 ? "l" : "r"));
    }
    // Names must be unique for a tool to tell the channels apart.
    for (std::size_t i = 0; i < names.size(); ++i)
        for (std::size_t j = 0; j < i; ++j)
            if (names[i] == names[j]) {
                for (std::size_t k = 0; k < names.size(); ++k)
                    names[k] = "wheel" + std::to_string(k);
                return names;
            }
    return names;
}

// Doubles with 9 significant digits: enough for every channel, compact for big files.
void number(std::ofstream& out, double x) {
    char text[32];
    std::snprintf(text, sizeof text, ",%.9g", x);
    out << text;
}

}  // namespace

TelemetryCsv::TelemetryCsv(const std::filesystem::path& file, const Car& car)
    : file_(file), out_(file, std::ios::binary) {
    if (!out_) throw Error("--telemetry '" + file.string() + "': cannot open it for writing");
    out_ << "time_s,speed_kmh,throttle,brake,steer";
    if (car.vehicle()) {
        out_ << ",engine_rpm,gear";
        for (const std::string& wheel : wheel_names(car.spec()))
            out_ << ',' << wheel << "_slip_ratio," << wheel << "_slip_angle_deg," << wheel
                 << "_load_n," << wheel << "_spin_rad_s";
    }
    out_ << '\n';
}

void TelemetryCsv::add(double time, const Car& car) {
    char text[32];
    std::snprintf(text, sizeof text, "%.2f", time);
    out_ << text;
    number(out_, car.speed() * 3.6);
    const CarInputs& in = car.inputs();
    number(out_, in.throttle), number(out_, in.brake), number(out_, in.steer);
    if (const Vehicle* vehicle = car.vehicle()) {
        number(out_, vehicle->engine_rpm());
        out_ << ',' << vehicle->state().gear;
        constexpr double kDegrees = 180.0 / 3.14159265358979323846;
        for (const WheelTelemetry& w : vehicle->telemetry()) {
            number(out_, w.slip_ratio), number(out_, std::atan(w.lateral_slip) * kDegrees);
            number(out_, w.load), number(out_, w.spin);
        }
    }
    out_ << '\n';
}

void TelemetryCsv::finish() {
    if (!out_.flush()) throw Error("--telemetry '" + file_.string() + "': cannot write it");
}

}  // namespace trackphys::cli
