#include "drive_session.hpp"

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
            s.autopilot = AutopilotProgress{a.at("nearest_sample").get<std::size_t>(),
                                            a.at("laps").get<int>(), a.at("located").get<bool>()};
        }
        s.distance_m = json.at("distance_m").get<double>();
        s.top_speed_kmh = json.at("top_speed_kmh").get<double>();
        s.lap_times_s = json.at("lap_times_s").get<std::vector<double>>();
        // Sessions saved before surfaces had none: every surface the dry road.
        if (json.contains("surface_grips"))
            s.surface_grips = json.at("surface_grips").get<std::vector<double>>();
        if (s.free_mode == s.autopilot.has_value())
            throw Error(s.free_mode ? "free mode with an autopilot" : "no autopilot progress");
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
