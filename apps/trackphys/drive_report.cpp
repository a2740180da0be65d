#include "drive_report.hpp"

#include <cinttypes>
#include <cstdio>

#include <nlohmann/json.hpp>

#include "json_file.hpp"

namespace trackphys::cli {
namespace {

void print_row(const char* name, const Summary& s) {
    std::printf("  %-10s %9.2f %9.2f %9.2f %9.2f\n", name, s.mean, s.p50, s.p99, s.max);
}

}  // namespace

nlohmann::json summary_json(const Summary& s) {
    return {{"mean", s.mean}, {"p50", s.p50}, {"p99", s.p99}, {"max", s.max}};
}

void add_profile_json(nlohmann::json& json, const ProfileStatistics& profile) {
    json["update_us"] = summary_json(profile.update_us());
    for (std::size_t p = 0; p < phase_count; ++p)
        json["phases_us"][phase_name(static_cast<Phase>(p))] =
            summary_json(profile.phase_us(static_cast<Phase>(p)));
}

void print_profile_table(const ProfileStatistics& profile) {
    std::printf("per update (us) %7s %9s %9s %9s\n", "mean", "p50", "p99", "max");
    print_row("update", profile.update_us());
    for (std::size_t p = 0; p < phase_count; ++p)
        print_row(phase_name(static_cast<Phase>(p)), profile.phase_us(static_cast<Phase>(p)));
    std::printf("  write-up budget: %.0f us typical, %.0f us spikes\n", kWriteupTypicalUs,
                kWriteupSpikeUs);
}

std::string hash_hex(std::uint64_t hash) {
    char text[17];
    std::snprintf(text, sizeof text, "%016" PRIx64, hash);
    return text;
}

void print_drive_report(const DriveReport& r) {
    std::printf("scene        %s, %zu triangles\n", r.scene.c_str(), r.triangles);
    std::printf("simulated    %.2f s in %" PRIu64 " updates (%.2f s wall clock)\n", r.simulated_s,
                r.updates, r.wall_s);
    std::printf("laps         %d", r.laps_completed);
    for (std::size_t i = 0; i < r.lap_times_s.size(); ++i)
        std::printf("%s%.2f s", i ? ", " : "  lap times ", r.lap_times_s[i]);
    std::printf("\n");
    std::printf("top speed    %.1f km/h\n", r.top_speed_kmh);
    std::printf("distance     %.1f m\n", r.distance_m);
    std::printf("final pos    (%.3f, %.3f, %.3f) m\n", r.final_position.x, r.final_position.y,
                r.final_position.z);
    print_profile_table(r.profile);
    std::printf(
        "counts per update: %.1f mid-phase queries, %.1f candidates, %.1f tested per "
        "ellipsoid sub-step, %.1f exact tests, %.1f contacts\n",
        r.profile.mean_mid_queries(), r.profile.mean_candidates(),
        r.profile.mean_tested_per_ellipsoid_substep(), r.profile.mean_exact_tests(),
        r.profile.mean_contacts());
    std::printf("resets       %" PRIu64 "%s%s\n", r.resets,
                r.last_reset.empty() ? "" : ", last at ", r.last_reset.c_str());
    std::printf("state hash   %s\n", hash_hex(r.state_hash).c_str());
}

void write_drive_json(const DriveReport& r, const std::filesystem::path& path) {
    nlohmann::json json;
    json["scene"] = r.scene;
    json["triangles"] = r.triangles;
    json["updates"] = r.updates;
    json["simulated_s"] = r.simulated_s;
    json["wall_s"] = r.wall_s;
    json["laps_completed"] = r.laps_completed;
    json["lap_time_s"] =
        r.lap_times_s.empty() ? nlohmann::json(nullptr) : nlohmann::json(r.lap_times_s.front());
    json["lap_times_s"] = r.lap_times_s;
    json["top_speed_kmh"] = r.top_speed_kmh;
    json["distance_m"] = r.distance_m;
    json["final_position"] = {r.final_position.x, r.final_position.y, r.final_position.z};
    json["state_hash"] = hash_hex(r.state_hash);
    json["resets"] = r.resets;
    add_profile_json(json, r.profile);
    json["counts"] = {
        {"mid_queries", r.profile.mean_mid_queries()},
        {"candidates", r.profile.mean_candidates()},
        {"tested_per_ellipsoid_substep", r.profile.mean_tested_per_ellipsoid_substep()},
        {"exact_tests", r.profile.mean_exact_tests()},
        {"contacts", r.profile.mean_contacts()}};
    json["writeup_budget_us"] = {{"typical", kWriteupTypicalUs}, {"spikes", kWriteupSpikeUs}};

    write_json_file(json, path);
}

}  // namespace trackphys::cli
