#include "recording_lines.hpp"

#include <algorithm>
#include <cmath>

#include <nlohmann/json.hpp>

#include "trackphys/error.hpp"

namespace trackphys::cli {
namespace {

using Json = nlohmann::json;

[[noreturn]] void refuse(const std::filesystem::path& path, std::size_t line,
                         const std::string& why) {
    throw Error("recording '" + path.string() + "': line " + std::to_string(line) + ": " + why);
}

// A JSON number that is a whole number in [low, high] (JavaScript reads 2.0 as 2 too).
bool whole_in(const Json& value, double low, double high) {
    if (!value.is_number()) return false;
    const double x = value.get<double>();
    return x >= low && x <= high && std::floor(x) == x;
}

struct Header {
    RecordingLines lines;
    std::vector<std::size_t> ellipsoids;  // per car; empty for a version 1 header
};

Header read_header(std::string_view text, const std::filesystem::path& path) {
    const Json header = Json::parse(text, nullptr, false);
    if (!header.is_object() || !header.contains("format") ||
        header["format"] != "trackphys-recording")
        throw Error("recording '" + path.string() +
                    "': not a trackphys recording (its first line must be a header with "
                    "\"format\":\"trackphys-recording\")");
    const Json& version = header.contains("version") ? header["version"] : Json();
    if (!whole_in(version, 1, 2))
        refuse(path, 1, "unknown recording version " + version.dump() + " (it reads 1 and 2)");
    if (!header.contains("dt") || !header["dt"].is_number() ||
        !std::isfinite(header["dt"].get<double>()))
        refuse(path, 1, "dt must be a finite number");
    if (!header.contains("cars") || !whole_in(header["cars"], 1, 1e9))
        refuse(path, 1, "cars must be a whole number >= 1");
    Header out;
    out.lines.cars = header["cars"].get<std::size_t>();
    if (version.get<double>() == 1) return out;
    const std::string all_cars = "car_ellipsoids must list the ellipsoids of all " +
                                 std::to_string(out.lines.cars) + " cars";
    const auto shapes = header.find("car_ellipsoids");
    if (shapes == header.end() || !shapes->is_array() || shapes->size() != out.lines.cars)
        refuse(path, 1, all_cars);
    for (const Json& shape : *shapes) {
        if (!shape.is_array() || shape.empty() ||
            !std::all_of(shape.begin(), shape.end(), [](const Json& e) { return e.is_object(); }))
            refuse(path, 1, all_cars);
        out.ellipsoids.push_back(shape.size());
    }
    if (const auto track = header.find("track"); track != header.end()) {
        if (!track->is_object() || !track->contains("mesh") || !(*track)["mesh"].is_string())
            refuse(path, 1, "track.mesh must be a file name");
        out.lines.track_mesh = (*track)["mesh"].get<std::string>();
    }
    return out;
}

// Why a frame's contacts between cars (absent: none touched) do not name the header's cars
// and ellipsoids, or empty when they do: the page would refuse them with these words.
std::string car_contacts_mismatch(const Json& frame, const Header& header) {
    const auto contacts = frame.find("car_contacts");
    if (contacts == frame.end()) return {};
    if (!contacts->is_array()) return "car_contacts must be an array";
    const double cars = static_cast<double>(header.lines.cars);
    // A version 1 header has no shapes: the page draws each car as one ellipsoid.
    const auto ellipsoids = [&](double car) {
        return header.ellipsoids.empty()
                   ? 1.0
                   : static_cast<double>(header.ellipsoids[static_cast<std::size_t>(car)]);
    };
    for (std::size_t i = 0; i < contacts->size(); ++i) {
        const Json& c = (*contacts)[i];
        const std::string what = "car_contacts[" + std::to_string(i) + "]";
        if (!c.is_array() || c.size() != 11 || !std::all_of(c.begin(), c.end(), [](const Json& x) {
                return x.is_number() && std::isfinite(x.get<double>());
            }))
            return what + " must be 11 finite numbers";
        if (!whole_in(c[0], 0, cars - 1) || !whole_in(c[1], 0, cars - 1) ||
            !(c[0].get<double>() < c[1].get<double>()))
            return what + " must name two of the " + std::to_string(header.lines.cars) +
                   " cars, the lower first";
        if (!whole_in(c[2], 0, ellipsoids(c[0].get<double>()) - 1) ||
            !whole_in(c[3], 0, ellipsoids(c[1].get<double>()) - 1))
            return what + " must name an ellipsoid of each car";
        if (!(c[10].get<double>() > 0.0)) return what + "'s depth must be > 0";
    }
    return {};
}

// Why a frame does not match its header, or empty when it does.
std::string frame_mismatch(const Json& frame, const Header& header) {
    const auto listed = frame.find("cars");
    if (listed == frame.end() || !listed->is_array() || listed->size() != header.lines.cars)
        return "it does not list the header's " + std::to_string(header.lines.cars) + " cars";
    for (std::size_t k = 0; k < header.ellipsoids.size(); ++k) {
        const Json& car = (*listed)[k];
        if (!car.is_object()) continue;
        const auto suspension = car.find("s");
        if (suspension != car.end() &&
            (!suspension->is_array() || suspension->size() != header.ellipsoids[k]))
            return "car " + std::to_string(k) + "'s \"s\" is not one number for each of its " +
                   std::to_string(header.ellipsoids[k]) + " ellipsoids in the header";
    }
    return car_contacts_mismatch(frame, header);
}

}  // namespace

RecordingLines check_recording_lines(std::string_view text, const std::filesystem::path& path) {
    const Header header = read_header(text.substr(0, text.find('\n')), path);
    std::size_t line = 1;
    double last_t = -INFINITY;
    for (std::size_t at = text.find('\n'); at != std::string_view::npos && at + 1 < text.size();) {
        ++line;
        const std::size_t end = std::min(text.find('\n', at + 1), text.size());
        const Json frame = Json::parse(text.substr(at + 1, end - at - 1), nullptr, false);
        // A recording cut short by a crash or a full disk ends in a line like this.
        if (!frame.is_object())
            refuse(path, line, "not a JSON object (a truncated or corrupt recording)");
        const auto t = frame.find("t");
        if (t == frame.end() || !t->is_number() || !std::isfinite(t->get<double>()))
            refuse(path, line, "t must be a finite number");
        if (!(t->get<double>() > last_t)) refuse(path, line, "t must increase from frame to frame");
        last_t = t->get<double>();
        if (const std::string why = frame_mismatch(frame, header); !why.empty())
            refuse(path, line, why);
        at = end;
    }
    if (line == 1) refuse(path, 1, "the recording has a header but no frames");
    return header.lines;
}

}  // namespace trackphys::cli
