#pragma once

// The harness every ellipsoid-triangle contact peer program shares: the case sets (the
// same generator, seed and mix as bench_contact), a long-double reference depth per case,
// timing per case, the error statistics, the table and the JSON. Each program measures
// ours in the same run, so every ratio it prints comes from one run on one machine.
//
// Timing: every case is run kRepeat times back to back between two steady_clock reads
// (warm caches and predictors, as in a contact loop over a car's candidates); the case's
// time is the mean of those calls. median_ns and mean_ns are over cases. The depth error
// of a method is |its depth - the reference depth| in metres; "touch" counts the cases where
// it disagrees with the reference on touching or not (depth > 0). Columns x_slower = median
// / ours's median and x_err_max = err_max / max(ours's err_max, 1e-15 m), on the same set.
// Sets: 20k hard-mix and 5k road cases (400 and 200 with --quick).

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "support/contact_cases.hpp"
#include "support/contact_reference.hpp"
#include "trackphys/geometry/contact.hpp"

namespace trackphys::peers {

/// One case: the ellipsoid, the triangle, the reference depth (m, > 0 overlapping) and the
/// generator's kind (road, edge, vertex, deep, miss).
struct PeerCase {
    Ellipsoid ellipsoid;
    Triangle triangle;
    double reference_depth;
    test::ContactKind kind;
};

/// A named case set: "hard_mix" (the benchmark's mix, 75% overlapping) or "road_shallow".
struct CaseSet {
    std::string name;
    std::vector<PeerCase> cases;
};

/// The long-double reference (tests/support/contact_reference.hpp) for a world case: the
/// triangle carried into the ellipsoid's sorted frame in long double, as contact_test does.
inline double reference_depth(const Ellipsoid& e, const Triangle& t) {
    using test::R;
    const glm::dmat3& m = e.sorted_axes();
    std::array<test::V3, 3> q;
    for (int i = 0; i < 3; ++i) {
        const test::V3 d{R(t[i].x) - R(e.center().x), R(t[i].y) - R(e.center().y),
                         R(t[i].z) - R(e.center().z)};
        q[i] = {d.x * m[0][0] + d.y * m[0][1] + d.z * m[0][2],
                d.x * m[1][0] + d.y * m[1][1] + d.z * m[1][2],
                d.x * m[2][0] + d.y * m[2][1] + d.z * m[2][2]};
    }
    const glm::dvec3 r = e.sorted_radii();
    return double(test::ContactReference({R(r.x), R(r.y), R(r.z)}, q).solve().depth);
}

/// The two sets, generated exactly as bench_contact does (seed 777, wheel and body
/// ellipsoids): `hard` cases of the hard mix and `road` shallow road contacts.
inline std::vector<CaseSet> make_case_sets(std::size_t hard, std::size_t road) {
    std::vector<CaseSet> sets{{"hard_mix", {}}, {"road_shallow", {}}};
    test::ContactCaseGenerator hard_generator(777, /*wheel_and_body=*/true);
    test::ContactCaseGenerator road_generator(777, /*wheel_and_body=*/true);
    const auto add = [](CaseSet& set, const test::ContactCase& c) {
        set.cases.push_back(
            {c.ellipsoid, c.triangle, reference_depth(c.ellipsoid, c.triangle), c.kind});
    };
    for (std::size_t i = 0; i < hard; ++i) add(sets[0], hard_generator.hard_mix());
    for (std::size_t i = 0; i < road; ++i)
        add(sets[1], road_generator.make(test::ContactKind::road));
    return sets;
}

/// A method's depth errors on the cases of one kind.
struct KindErrors {
    std::size_t cases = 0, over_1mm = 0;
    double max = 0;  ///< m
};

/// One method's figures on one set.
struct MethodResult {
    std::string method;  ///< e.g. "trackphys", "bullet_float_gjk_epa"
    std::string set;
    std::size_t cases = 0;
    double median_ns = 0, mean_ns = 0;
    double error_median = 0, error_p99 = 0, error_max = 0;  ///< |depth - reference| (m)
    std::size_t touch_disagreements = 0;                    ///< (depth > 0) != (reference > 0)
    std::size_t over_1mm = 0;  ///< cases whose depth is off by more than 1 mm
    std::size_t failures = 0;  ///< the peer reported a failure (its depth counted as 0)
    std::array<KindErrors, std::size_t(test::ContactKind::count)> by_kind{};
};

/// What a method returns for one case: the signed depth (m) and whether it failed.
struct PeerDepth {
    double depth;
    bool failed;
};

constexpr int kRepeat = 8;

/// Times and checks `query` (PeerDepth(std::size_t case index)) over a set.
template <class Query>
MethodResult measure(const std::string& method, const CaseSet& set, Query&& query) {
    MethodResult result{method, set.name, set.cases.size()};
    std::vector<double> ns(set.cases.size()), error(set.cases.size());
    for (std::size_t i = 0; i < set.cases.size(); ++i) {
        PeerDepth got{0.0, false};
        const auto start = std::chrono::steady_clock::now();
        for (int k = 0; k < kRepeat; ++k) got = query(i);
        const auto stop = std::chrono::steady_clock::now();
        ns[i] = std::chrono::duration<double, std::nano>(stop - start).count() / kRepeat;
        const double reference = set.cases[i].reference_depth;
        const double depth = got.failed || !std::isfinite(got.depth) ? 0.0 : got.depth;
        result.failures += got.failed || !std::isfinite(got.depth);
        error[i] = std::abs(depth - reference);
        result.over_1mm += error[i] > 1e-3;
        KindErrors& kind = result.by_kind[std::size_t(set.cases[i].kind)];
        ++kind.cases;
        kind.over_1mm += error[i] > 1e-3;
        kind.max = std::max(kind.max, error[i]);
        result.touch_disagreements += (depth > 0.0) != (reference > 0.0);
    }
    double sum = 0;
    for (double t : ns) sum += t;
    result.mean_ns = sum / double(ns.size());
    const auto quantile = [](std::vector<double>& v, double q) {
        const auto k = static_cast<std::size_t>(q * double(v.size() - 1));
        std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
        return v[k];
    };
    result.median_ns = quantile(ns, 0.5);
    result.error_median = quantile(error, 0.5);
    result.error_p99 = quantile(error, 0.99);
    result.error_max = *std::max_element(error.begin(), error.end());
    return result;
}

/// Ours on a set: the library's exact kernel.
inline MethodResult measure_ours(const CaseSet& set) {
    return measure("trackphys", set, [&](std::size_t i) {
        const PeerCase& c = set.cases[i];
        return PeerDepth{ellipsoid_triangle_contact(c.ellipsoid, c.triangle).depth, false};
    });
}

/// Command line of every peer program: --quick (a few hundred cases, for the tests and
/// `trackphys-bench --quick`) and --json FILE.
struct Options {
    bool quick = false;
    std::string json;
    std::size_t hard_cases() const { return quick ? 400 : 20000; }
    std::size_t road_cases() const { return quick ? 200 : 5000; }
};

inline Options parse_options(int argc, char** argv, const char* usage) {
    Options options;
    for (int i = 1; i < argc; ++i) {
        const std::string_view arg = argv[i];
        if (arg == "--quick") {
            options.quick = true;
        } else if (arg == "--json" && i + 1 < argc) {
            options.json = argv[++i];
        } else {
            std::fprintf(stderr, "%s: unknown argument '%s'\nusage: %s [--quick] [--json FILE]\n",
                         argv[0], argv[i], usage);
            std::exit(2);
        }
    }
    return options;
}

/// The table: each method beside ours on the same set, with the speed and accuracy ratios.
inline void print_table(const std::vector<MethodResult>& results) {
    std::printf("%-26s %-13s %6s %9s %9s %10s %10s %10s %6s %6s %5s %8s %9s\n", "method", "set",
                "cases", "median_ns", "mean_ns", "err_median", "err_p99", "err_max", ">1mm",
                "touch", "fail", "x_slower", "x_err_max");
    for (const MethodResult& r : results) {
        const MethodResult* ours = nullptr;
        for (const MethodResult& o : results)
            if (o.method == "trackphys" && o.set == r.set) ours = &o;
        const double slower = ours ? r.median_ns / ours->median_ns : 0.0;
        // Our errors are ~1e-16 m or exactly 0: a floor of 1e-15 m keeps the ratio finite.
        const double worse = ours ? r.error_max / std::max(ours->error_max, 1e-15) : 0.0;
        std::printf(
            "%-26s %-13s %6zu %9.1f %9.1f %10.3g %10.3g %10.3g %6zu %6zu %5zu %8.1f %9.3g\n",
            r.method.c_str(), r.set.c_str(), r.cases, r.median_ns, r.mean_ns, r.error_median,
            r.error_p99, r.error_max, r.over_1mm, r.touch_disagreements, r.failures, slower, worse);
    }
    std::printf("\nby kind: max |depth error| (m) / cases off by more than 1 mm / cases\n");
    for (const MethodResult& r : results) {
        std::printf("%-26s %-13s", r.method.c_str(), r.set.c_str());
        for (std::size_t k = 0; k < r.by_kind.size(); ++k)
            if (r.by_kind[k].cases > 0)
                std::printf("  %s %.3g/%zu/%zu", test::contact_kind_name(test::ContactKind(k)),
                            r.by_kind[k].max, r.by_kind[k].over_1mm, r.by_kind[k].cases);
        std::printf("\n");
    }
}

/// Writes {"program": ..., "repeat": ..., "results": [...]} (units: ns and metres).
inline bool write_json(const std::string& path, const char* program,
                       const std::vector<MethodResult>& results) {
    std::FILE* f = std::fopen(path.c_str(), "w");
    if (!f) {
        std::fprintf(stderr, "%s: cannot write '%s'\n", program, path.c_str());
        return false;
    }
    std::fprintf(f, "{\n  \"program\": \"%s\",\n  \"kind\": \"ellipsoid_triangle_contact\",\n",
                 program);
    std::fprintf(f, "  \"repeat\": %d,\n  \"results\": [\n", kRepeat);
    for (std::size_t i = 0; i < results.size(); ++i) {
        const MethodResult& r = results[i];
        std::fprintf(f,
                     "    {\"method\": \"%s\", \"set\": \"%s\", \"cases\": %zu, "
                     "\"median_ns\": %.6g, \"mean_ns\": %.6g, \"depth_error_median_m\": %.6g, "
                     "\"depth_error_p99_m\": %.6g, \"depth_error_max_m\": %.6g, "
                     "\"depth_error_over_1mm\": %zu, \"touch_disagreements\": %zu, "
                     "\"failures\": %zu, \"by_kind\": {",
                     r.method.c_str(), r.set.c_str(), r.cases, r.median_ns, r.mean_ns,
                     r.error_median, r.error_p99, r.error_max, r.over_1mm, r.touch_disagreements,
                     r.failures);
        const char* separator = "";
        for (std::size_t k = 0; k < r.by_kind.size(); ++k)
            if (r.by_kind[k].cases > 0) {
                std::fprintf(f, "%s\"%s\": {\"cases\": %zu, \"over_1mm\": %zu, \"max_m\": %.6g}",
                             separator, test::contact_kind_name(test::ContactKind(k)),
                             r.by_kind[k].cases, r.by_kind[k].over_1mm, r.by_kind[k].max);
                separator = ", ";
            }
        std::fprintf(f, "}}%s\n", i + 1 < results.size() ? "," : "");
    }
    std::fprintf(f, "  ]\n}\n");
    return std::fclose(f) == 0;
}

/// The whole program: sets, ours, then each peer method, table, JSON. Exit code 0 when
/// everything ran, ours met its own contract (error <= 1e-9 m on every case) and every peer
/// answered and agreed on touching or not on at least 90% of the cases (less means the
/// adapter is broken - a sign convention, a margin left on - not that the peer is weak).
/// A peer method: its name and, per case set, the query for case i. prepare runs untimed,
/// so a peer can build what a real user would keep between queries (FCL's convex shapes).
struct Peer {
    std::string name;
    std::function<std::function<PeerDepth(std::size_t)>(const CaseSet&)> prepare;
};

/// A peer that needs nothing prepared: `query` answers one case.
inline Peer per_case(std::string name, std::function<PeerDepth(const PeerCase&)> query) {
    return {std::move(name), [query](const CaseSet& set) {
                return std::function<PeerDepth(std::size_t)>(
                    [&set, query](std::size_t i) { return query(set.cases[i]); });
            }};
}

inline int run_contact_peers(int argc, char** argv, const char* program,
                             const std::vector<Peer>& peers) {
    const Options options = parse_options(argc, argv, program);
    std::fprintf(stderr, "%s: generating cases and long-double references...\n", program);
    const std::vector<CaseSet> sets = make_case_sets(options.hard_cases(), options.road_cases());
    std::vector<MethodResult> results;
    for (const CaseSet& set : sets) {
        std::fprintf(stderr, "%s: %s (%zu cases)\n", program, set.name.c_str(), set.cases.size());
        results.push_back(measure_ours(set));
        for (const Peer& peer : peers) {
            const std::function<PeerDepth(std::size_t)> query = peer.prepare(set);
            results.push_back(measure(peer.name, set, query));
        }
    }
    print_table(results);
    bool ok = true;
    for (const MethodResult& r : results) {
        if (r.method == "trackphys" && r.error_max > 1e-9) {
            std::fprintf(stderr, "%s: ours broke its 1e-9 m contract on %s\n", program,
                         r.set.c_str());
            ok = false;
        }
        if (10 * (r.failures + r.touch_disagreements) > r.cases) {
            std::fprintf(stderr, "%s: %s fails or disagrees on touching on over 10%% of %s\n",
                         program, r.method.c_str(), r.set.c_str());
            ok = false;
        }
    }
    if (!options.json.empty()) ok = write_json(options.json, program, results) && ok;
    return ok ? 0 : 1;
}

}  // namespace trackphys::peers
