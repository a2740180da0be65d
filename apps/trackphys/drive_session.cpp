#include "drive_session.hpp"

#include <cmath>
#include <limits>
#include <sstream>

#include <nlohmann/json.hpp>

#include "trackphys/error.hpp"

namespace trackphys::cli {

std::string session_json(const DriveSession& s) {
    nlohmann::json json;
    json["format"] = "trackphys-drive-session";
    json["free_mode"] = s.free_mode;
    json["seed"] = s.seed;
    json["target_speed_kmh"] = s.target_speed_kmh;
    json["throttle"] = s.throttle;
    json["steer"] = s.steer;
    if (s.autopilot)
        json["autopilot"] = {{"nearest_sample", s.autopilot->nearest_sample},
                             {"laps", s.autopilot->laps},
                             {"located", s.autopilot->located}};
    json["distance_m"] = s.distance_m;
    json["top_speed_kmh"] = s.top_speed_kmh;
    json["lap_times_s"] = s.lap_times_s;
    json["surface_grips"] = s.surface_grips;
    return json.dump();
}

namespace {

// A whole number from 0 to `most`: get<int>() would wrap 2^32 + 5 to 5 and truncate 1.5.
std::uint64_t whole(const nlohmann::json& json, const char* key, std::uint64_t most) {
    const nlohmann::json& value = json.at(key);
    if (!value.is_number_unsigned() || value.get<std::uint64_t>() > most)
        throw Error(std::string(key) + " is not a whole number from 0 to " + std::to_string(most));
    return value.get<std::uint64_t>();
}

// The running figures a report prints: what a drive can have made of them. The checksum
// guards against damage, not against an edited file re-sealed.
void check_figures(const DriveSession& s) {
    if (!(std::isfinite(s.distance_m) && s.distance_m >= 0.0))
        throw Error("distance_m is not finite and >= 0");
    if (!(std::isfinite(s.top_speed_kmh) && s.top_speed_kmh >= 0.0))
        throw Error("top_speed_kmh is not finite and >= 0");
    for (const double lap : s.lap_times_s)
        if (!(std::isfinite(lap) && lap > 0.0)) throw Error("a lap time is not finite and > 0");
    // Fewer laps than lap times when the car has crossed the line backwards since.
    if (s.autopilot && static_cast<std::size_t>(s.autopilot->laps) > s.lap_times_s.size())
        throw Error("autopilot.laps is more than the lap times");
}

}  // namespace

DriveSession parse_session(std::string_view text) {
    try {
        const nlohmann::json json = nlohmann::json::parse(text);
        if (json.at("format") != "trackphys-drive-session") throw Error("not a drive session");
        DriveSession s;
        s.free_mode = json.at("free_mode").get<bool>();
        s.seed = json.at("seed").get<std::uint64_t>();
        s.target_speed_kmh = json.at("target_speed_kmh").get<double>();
        s.throttle = json.at("throttle").get<double>();
        s.steer = json.at("steer").get<double>();
        if (json.contains("autopilot")) {
            const nlohmann::json& a = json.at("autopilot");
            constexpr std::uint64_t most_laps = std::numeric_limits<int>::max() / 2;
            s.autopilot = AutopilotProgress{
                static_cast<std::size_t>(whole(a, "nearest_sample", std::size_t(-1))),
                static_cast<int>(whole(a, "laps", most_laps)), a.at("located").get<bool>()};
        }
        s.distance_m = json.at("distance_m").get<double>();
        s.top_speed_kmh = json.at("top_speed_kmh").get<double>();
        s.lap_times_s = json.at("lap_times_s").get<std::vector<double>>();
        // Sessions saved before surfaces had none: every surface the dry road.
        if (json.contains("surface_grips"))
            s.surface_grips = json.at("surface_grips").get<std::vector<double>>();
        if (s.free_mode == s.autopilot.has_value())
            throw Error(s.free_mode ? "free mode with an autopilot" : "no autopilot progress");
        check_figures(s);
        return s;
    } catch (const nlohmann::json::parse_error&) {
        // A snapshot saved by the library (save_snapshot) rather than by the command.
        throw Error(
            "the snapshot holds no drive session: it was not saved by `trackphys drive "
            "--save-at`");
    } catch (const nlohmann::json::exception& e) {
        throw Error(std::string("the snapshot's drive session is not valid: ") + e.what());
    } catch (const Error& e) {
        throw Error(std::string("the snapshot's drive session is not valid: ") + e.what());
    }
}

namespace {

std::string grips_option(const std::vector<double>& grips) {
    if (grips.empty()) return "no --surface-grips";
    std::ostringstream text;
    text << "--surface-grips ";
    for (std::size_t i = 0; i < grips.size(); ++i) text << (i ? "," : "") << grips[i];
    return text.str();
}

}  // namespace

void check_same_drive(const DriveSession& saved, const DriveSession& now) {
    std::ostringstream why;
    if (saved.free_mode != now.free_mode)
        why << "the snapshot was made "
            << (saved.free_mode ? "in free mode (--mesh, --spawn)" : "on a generated track");
    else if (!saved.free_mode && saved.seed != now.seed)
        why << "the snapshot was made with --seed " << saved.seed << ", this drive has "
            << now.seed;
    else if (!saved.free_mode && saved.target_speed_kmh != now.target_speed_kmh)
        why << "the snapshot was made with --target-speed " << saved.target_speed_kmh
            << ", this drive has " << now.target_speed_kmh;
    else if (saved.free_mode && (saved.throttle != now.throttle || saved.steer != now.steer))
        why << "the snapshot was made with --throttle " << saved.throttle << " --steer "
            << saved.steer << ", this drive has " << now.throttle << ' ' << now.steer;
    else if (saved.surface_grips != now.surface_grips)
        why << "the snapshot was made with " << grips_option(saved.surface_grips)
            << ", this drive has " << grips_option(now.surface_grips);
    if (why.tellp() > 0)
        throw Error("--resume: " + why.str() + " (resume with the original drive's options)");
}

}  // namespace trackphys::cli
