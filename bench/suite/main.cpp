// trackphys-bench [--quick] [--only GROUPS] [--json FILE] [--check]: every comparison of the
// benchmarks in one run on this machine, printed as one table (and JSON), with the peers
// found and the target lines checked.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "bench_suite.hpp"
#include "drive_report.hpp"
#include "json_file.hpp"
#include "staged_outputs.hpp"
#include "trackphys/build_target.hpp"
#include "trackphys/error.hpp"

namespace trackphys::suite {

BenchRun::BenchRun(bool quick) : quick_(quick), terminal_(isatty(2) != 0) {}

void BenchRun::progress(const std::string& group, const std::string& what) {
    if (!terminal_) return;
    std::fprintf(stderr, "\r%-79.79s", ("[" + group + "] " + what + "...").c_str());
    std::fflush(stderr);
}

void BenchRun::end_progress() {
    if (terminal_) std::fprintf(stderr, "\r%79s\r", "");
}

BenchRow& BenchRun::add(std::string group, std::string name, double median_ns, std::string versus) {
    BenchRow row{std::move(group), std::move(name), median_ns, 1.0, std::move(versus), {}, {}};
    if (!row.versus.empty()) row.ratio = median_ns / this->row(row.group, row.versus).median_ns;
    rows_.push_back(std::move(row));
    return rows_.back();
}

void BenchRun::add_target(std::string what, double value, double target, bool correct,
                          std::string evidence) {
    targets_.push_back({std::move(what), value, target, correct, std::move(evidence)});
}

const BenchRow& BenchRun::row(const std::string& group, const std::string& name) const {
    for (const BenchRow& r : rows_)
        if (r.group == group && r.name == name) return r;
    throw Error("bench: no row '" + name + "' in group '" + group + "'");
}

namespace {

struct Group {
    const char* name;
    void (*run)(BenchRun&);
    bool by_default = true;  ///< false: minutes long, run only when --only names it
};

// Table order: the write-up's improvements, then the peers.
constexpr Group kGroups[] = {{"cull", bench_cull},
                             {"roots", bench_roots},
                             {"broad", bench_broad_phase},
                             {"mid", bench_mid_phase},
                             {"update", bench_update},
                             {"vehicle", bench_vehicle},
                             {"maps", bench_maps},
                             {"colliders", bench_many_colliders},
                             {"bigmap", bench_big_map, false},
                             {"race", bench_race},
                             {"contact", bench_contact_peers},
                             {"pair", bench_pair_peers},
                             {"mesh", bench_mesh_peers},
                             {"bullet_update", bench_update_peers}};

/// A time with a readable unit: 812 ns, 3.41 us, 2.05 ms.
std::string format_time(double ns) {
    char text[32];
    if (ns <= 0.0) return "-";
    if (ns < 1e3)
        std::snprintf(text, sizeof text, "%.0f ns", ns);
    else if (ns < 1e6)
        std::snprintf(text, sizeof text, "%.3g us", ns * 1e-3);
    else
        std::snprintf(text, sizeof text, "%.3g ms", ns * 1e-6);
    return text;
}

std::string format_figures(const BenchRow& row) {
    std::ostringstream out;
    for (const auto& [key, value] : row.figures) {
        char number[32];
        std::snprintf(number, sizeof number, "%.3g", value);
        out << key << '=' << number << "  ";
    }
    if (!row.note.empty()) out << "(" << row.note << ")";
    return out.str();
}

/// Printed before the run, so the peers found are known while it runs.
void print_header(bool quick, const std::vector<PeerStatus>& peers) {
    std::printf(
        "trackphys-bench%s: median time of one call; x = median / the 'vs' row's median\n"
        "  (update groups: the thread's CPU time per update, so that a busy machine's\n"
        "  other processes do not count)\n",
        quick ? " --quick" : "");
    std::printf("  trackphys built for %s; the peers are Debian's builds (x86-64 baseline)\n",
                trackphys::build_target());
    for (const PeerStatus& p : peers)
        std::printf("  peer %-14s %s (%s)\n", p.name.c_str(), p.built ? "built" : "not built",
                    p.detail.c_str());
    std::fflush(stdout);
}

void print_table(const BenchRun& run, double wall_s) {
    std::printf("\n%-14s %-52s %10s %9s  %-34s %s\n", "group", "case", "median", "x", "vs",
                "figures");
    std::string last_group;
    for (const BenchRow& r : run.rows()) {
        if (r.group != last_group && !last_group.empty()) std::printf("\n");
        last_group = r.group;
        char ratio[32] = "";
        if (!r.versus.empty() && r.median_ns > 0.0)
            std::snprintf(ratio, sizeof ratio, "%.3g", r.ratio);
        std::printf("%-14s %-52s %10s %9s  %-34s %s\n", r.group.c_str(), r.name.c_str(),
                    format_time(r.median_ns).c_str(), ratio, r.versus.c_str(),
                    format_figures(r).c_str());
    }
    if (!run.targets().empty())
        std::printf(
            "\nthe issues' targets on this machine%s:\n",
            run.quick() ? " (--quick: fewer cases on colder caches; the full run decides)" : "");
    for (const BenchTarget& t : run.targets()) {
        std::printf("  %-4s %-70s %10.3g  (target >= %g)", t.met() ? "met" : "MISS", t.what.c_str(),
                    t.value, t.target);
        if (!t.evidence.empty())
            std::printf("  %s%s", t.correct ? "" : "NOT CORRECT: ", t.evidence.c_str());
        std::printf("\n");
    }
    std::printf("\nwall time %.1f s\n", wall_s);
}

nlohmann::json to_json(const BenchRun& run, const std::vector<PeerStatus>& peers, double wall_s) {
    nlohmann::json json;
    json["quick"] = run.quick();
    json["build_target"] = trackphys::build_target();
    json["wall_s"] = wall_s;
    json["writeup_budget_us"] = {{"typical", cli::kWriteupTypicalUs},
                                 {"spikes", cli::kWriteupSpikeUs}};
    for (const PeerStatus& p : peers)
        json["peers"][p.key] = {{"name", p.name}, {"built", p.built}, {"detail", p.detail}};
    json["rows"] = nlohmann::json::array();
    for (const BenchRow& r : run.rows()) {
        nlohmann::json row = {{"group", r.group}, {"case", r.name},     {"median_ns", r.median_ns},
                              {"ratio", r.ratio}, {"versus", r.versus}, {"note", r.note}};
        row["figures"] = nlohmann::json::object();
        // JSON has no NaN or infinity: a figure that is not finite is written as null.
        for (const auto& [key, value] : r.figures)
            row["figures"][key] =
                std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
        json["rows"].push_back(std::move(row));
    }
    json["targets"] = nlohmann::json::array();
    for (const BenchTarget& t : run.targets())
        json["targets"].push_back({{"what", t.what},
                                   {"value", t.value},
                                   {"target", t.target},
                                   {"correct", t.correct},
                                   {"evidence", t.evidence},
                                   {"met", t.met()}});
    return json;
}

/// Runs the selected groups and prints (and writes) the table; returns the number of target
/// lines that say MISS.
int run_bench(const BenchOptions& o) {
    for (const std::string& name : o.only) {
        bool known = false;
        for (const Group& g : kGroups) known = known || name == g.name;
        if (!known)
            throw Error("--only '" + name +
                        "': not a group (cull, roots, broad, mid, update, vehicle, maps, "
                        "colliders, bigmap, "
                        "race, "
                        "contact, pair, mesh, "
                        "bullet_update)");
    }
    // Checked and staged before minutes of measuring; put in place only after the run.
    cli::StagedOutputs outputs;
    const std::filesystem::path json = o.json.empty() ? o.json : outputs.stage(o.json, "--json");
    const std::vector<PeerStatus> peers = peer_status();
    print_header(o.quick, peers);
    BenchRun run(o.quick);
    const auto start = std::chrono::steady_clock::now();
    for (const Group& g : kGroups) {
        bool selected = o.only.empty() && g.by_default;
        for (const std::string& name : o.only) selected = selected || name == g.name;
        if (selected) g.run(run);
    }
    run.end_progress();
    const double wall_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    print_table(run, wall_s);
    if (!json.empty()) {
        cli::write_json_file(to_json(run, peers, wall_s), json);
        outputs.commit();
    }
    return int(std::count_if(run.targets().begin(), run.targets().end(),
                             [](const BenchTarget& t) { return !t.met(); }));
}

/// The exit status when a target line says MISS.
constexpr int kMissExit = 3;

}  // namespace
}  // namespace trackphys::suite

int main(int argc, char** argv) {
    using namespace trackphys;
    if (!cpu_runs_build_target()) {
        std::fprintf(stderr,
                     "trackphys-bench: error: this build is for %s CPUs and this one lacks some of "
                     "its instructions; rebuild with cmake -DTRACKPHYS_X86_64_LEVEL=v1\n",
                     build_target());
        return 1;
    }
    suite::BenchOptions o;
    CLI::App app{
        "trackphys-bench: every comparison of the benchmarks on this machine in one run: the "
        "write-up's improvements (cull, roots, broad and mid phase, whole update vs its "
        "budget) and the peers (Bullet, FCL, MuJoCo) where built; prints one table of medians and "
        "ratios and the target lines",
        "trackphys-bench"};
    app.add_flag("--quick", o.quick,
                 "Fewer cases and repeats, colder caches: a smoke run, not the measure");
    app.add_option("--only", o.only,
                   "Run only these groups (cull, roots, broad, mid, update, vehicle, maps, "
                   "colliders, bigmap (only when named: minutes long), race, "
                   "contact, pair, mesh, bullet_update), comma-separated")
        ->delimiter(',');
    app.add_option("--json", o.json, "Write the table as JSON (atomically)");
    app.add_flag("--check", o.check, "Fail on a MISS in any mode (a full run always does)");
    app.footer(
        "Exit status: 0 when every target line printed is met; 3 when one says MISS in a full "
        "run, or in a --quick run with --check (without --check a --quick run reports MISS "
        "and exits 0: its cold caches do not decide); 1 on an error.");
    try {
        app.parse(argc, argv);
        const int missed = suite::run_bench(o);
        if (missed > 0 && (!o.quick || o.check)) {
            std::fprintf(stderr, "trackphys-bench: %d target line%s MISS\n", missed,
                         missed == 1 ? " says" : "s say");
            return suite::kMissExit;
        }
    } catch (const CLI::ParseError& e) {
        return app.exit(e);
    } catch (const Error& e) {
        std::fprintf(stderr, "trackphys-bench: error: %s\n", e.what());
        return 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "trackphys-bench: unexpected error: %s\n", e.what());
        return 1;
    }
    return 0;
}
