#include "race_report.hpp"

#include <algorithm>
#include <cinttypes>
#include <cstdio>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "drive_report.hpp"
#include "json_file.hpp"

namespace trackphys::cli {
namespace {

// "-" for a car that has not finished a lap: a time of 0.00 would read as a lap.
std::string lap_text(const std::vector<double>& lap_times_s, bool best) {
    if (lap_times_s.empty()) return "-";
    char text[32];
    std::snprintf(
        text, sizeof text, "%.2f",
        best ? *std::min_element(lap_times_s.begin(), lap_times_s.end()) : lap_times_s.back());
    return text;
}

double per_car_us(const RaceReport& r) {
    return r.cars == 0 ? 0.0 : r.profile.update_us().mean / static_cast<double>(r.cars);
}

}  // namespace

void print_race_report(const RaceReport& r) {
    std::printf("scene        %s\n", r.scene.c_str());
    std::printf("race         %zu car%s on %d thread%s, %.2f s simulated in %" PRIu64
                " updates (%.2f s wall clock)\n",
                r.cars, r.cars == 1 ? "" : "s", r.threads, r.threads == 1 ? "" : "s", r.simulated_s,
                r.updates, r.wall_s);
    std::printf("%4s %4s %8s %6s %5s %10s %10s %7s\n", "pos", "car", "km/h", "grip %", "laps",
                "best lap", "last lap", "resets");
    for (std::size_t i = 0; i < r.classification.size(); ++i) {
        const RaceCarResult& c = r.classification[i];
        std::printf("%4zu %4zu %8.0f %6.1f %5d %10s %10s %7" PRIu64 "\n", i + 1, c.car,
                    c.target_kmh, 100.0 * c.grip_use, c.laps, lap_text(c.lap_times_s, true).c_str(),
                    lap_text(c.lap_times_s, false).c_str(), c.resets);
    }
    std::printf("laps         %d by every car\n", r.laps_completed);
    std::printf("car contacts %" PRIu64 " sub-steps of touching pairs, deepest %.4f m\n",
                r.car_contacts, r.max_car_penetration_m);
    std::printf("events       %" PRIu64 " car touches begun, %" PRIu64 " body hits\n",
                r.car_touches, r.body_hits);
    print_profile_table(r.profile);
    std::printf("per car      %.2f us per car-update (mean update / cars)\n", per_car_us(r));
    std::printf("resets       %" PRIu64 " (%" PRIu64 " of them rescues off the track)\n", r.resets,
                r.rescues);
    std::printf("state hash   %s\n", hash_hex(r.state_hash).c_str());
}

void write_race_json(const RaceReport& r, const std::filesystem::path& path) {
    nlohmann::json json;
    json["scene"] = r.scene;
    json["cars"] = r.cars;
    json["threads"] = r.threads;
    json["updates"] = r.updates;
    json["simulated_s"] = r.simulated_s;
    json["wall_s"] = r.wall_s;
    json["laps_completed"] = r.laps_completed;
    add_profile_json(json, r.profile);
    json["per_car_us"] = per_car_us(r);
    json["car_contacts"] = r.car_contacts;
    json["max_car_penetration_m"] = r.max_car_penetration_m;
    json["car_touches"] = r.car_touches;
    json["body_hits"] = r.body_hits;
    json["resets"] = r.resets;
    json["rescues"] = r.rescues;
    json["state_hash"] = hash_hex(r.state_hash);
    nlohmann::json classification = nlohmann::json::array();
    for (const RaceCarResult& c : r.classification)
        classification.push_back({{"car", c.car},
                                  {"target_kmh", c.target_kmh},
                                  {"grip_use", c.grip_use},
                                  {"laps", c.laps},
                                  {"lap_times_s", c.lap_times_s},
                                  {"resets", c.resets},
                                  {"rescues", c.rescues}});
    json["classification"] = std::move(classification);
    write_json_file(json, path);
}

}  // namespace trackphys::cli
