#pragma once

// The ellipsoid-ellipsoid peer comparison (issue 15): ours and each peer method on the same
// pairs of every family (tests/support/ellipsoid_pair_cases.hpp), each pair's depth checked
// against the long-double reference. Prints, per family and method, the median time per
// pair (each pair timed over 16 back-to-back calls), the largest depth error and the
// failures (no answer), then the target lines, each "met" only when our contract
// (1e-9 m, 1e-11 relative beyond 100 m) held on every pair of the run.
//
// Peers whose libraries share symbol names (Bullet float and double) live in separate
// programs, so each program compares ours with its own peers; trackphys-bench's "pair"
// group (bench/suite/pair_group.cpp) runs ours, Bullet float, FCL and MuJoCo in one run on
// the same families.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <functional>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "support/ellipsoid_pair_cases.hpp"
#include "support/ellipsoid_pair_reference.hpp"
#include "trackphys/geometry/ellipsoid_pair.hpp"

namespace trackphys::peers {

struct PairPeerDepth {
    double depth;  ///< our convention: > 0 overlapping, -distance apart
    bool failed;   ///< the method gave no answer
};

struct PairPeer {
    std::string name;
    std::function<PairPeerDepth(const Ellipsoid&, const Ellipsoid&)> depth;
};

struct PairFamily {
    test::PairKind kind;
    std::vector<test::PairCase> cases;
    std::vector<double> reference;
};

struct PairScore {
    /// Time per pair over the family: its median (the typical pair), mean (what a frame of
    /// many pairs pays, searched pairs included) and 99th percentile.
    double median_ns = 0, mean_ns = 0, p99_ns = 0;
    double max_error = 0;
    int failures = 0;
    std::string worst;  ///< the pair with the largest error
};

/// `call(i)` (pair i's depth) timed over 16 back-to-back calls per pair of the family and
/// scored against the reference.
template <class Call>
PairScore score_calls(const PairFamily& family, const Call& call) {
    constexpr int kPairRepeat = 16;
    PairScore s;
    std::vector<double> ns;
    for (std::size_t i = 0; i < family.cases.size(); ++i) {
        PairPeerDepth answer{};
        const auto start = std::chrono::steady_clock::now();
        for (int k = 0; k < kPairRepeat; ++k) answer = call(i);
        const auto stop = std::chrono::steady_clock::now();
        ns.push_back(std::chrono::duration<double, std::nano>(stop - start).count() / kPairRepeat);
        if (answer.failed) {
            ++s.failures;
            continue;
        }
        const double error = std::abs(answer.depth - family.reference[i]);
        if (!(error <= s.max_error)) {
            s.max_error = std::isnan(error) ? INFINITY : error;
            char buffer[160];
            std::snprintf(buffer, sizeof buffer, "pair %zu: got %.12g want %.12g", i, answer.depth,
                          family.reference[i]);
            s.worst = buffer;
        }
    }
    std::sort(ns.begin(), ns.end());
    s.median_ns = ns[ns.size() / 2];
    s.p99_ns = ns[ns.size() * 99 / 100];
    for (const double t : ns) s.mean_ns += t / static_cast<double>(ns.size());
    return s;
}

inline PairScore score(const PairPeer& peer, const PairFamily& family) {
    return score_calls(
        family, [&](std::size_t i) { return peer.depth(family.cases[i].a, family.cases[i].b); });
}

/// A method started from the normal of the pair's earlier contact (a warm start).
struct WarmPairPeer {
    std::string name;
    std::function<PairPeerDepth(const Ellipsoid&, const Ellipsoid&, const glm::dvec3&)> depth;
};

/// A family's pairs with, for each, the normal of its contact one physics sub-step earlier
/// (test::PairCaseGenerator::earlier) and the angle between the two contacts' normals.
struct WarmPairFamily {
    PairFamily family;
    std::vector<glm::dvec3> starts;
    std::vector<double> turn;  ///< rad
};

inline WarmPairFamily make_warm_pairs(const PairFamily& family, std::uint64_t seed) {
    test::PairCaseGenerator generator(seed);
    WarmPairFamily warm{family, {}, {}};
    for (const test::PairCase& c : family.cases) {
        const test::PairCase before = generator.earlier(c);
        const glm::dvec3 start = ellipsoid_ellipsoid_contact(before.a, before.b).normal;
        const glm::dvec3 now = ellipsoid_ellipsoid_contact(c.a, c.b).normal;
        warm.starts.push_back(start);
        warm.turn.push_back(std::atan2(glm::length(glm::cross(start, now)), glm::dot(start, now)));
    }
    return warm;
}

inline PairScore score(const WarmPairPeer& peer, const WarmPairFamily& warm) {
    return score_calls(warm.family, [&](std::size_t i) {
        return peer.depth(warm.family.cases[i].a, warm.family.cases[i].b, warm.starts[i]);
    });
}

/// Ours, as a method of the comparison.
inline PairPeer ours_pair_peer() {
    return {"trackphys", [](const Ellipsoid& a, const Ellipsoid& b) {
                return PairPeerDepth{ellipsoid_ellipsoid_contact(a, b).depth, false};
            }};
}

/// Ours started from the earlier contact's normal.
inline WarmPairPeer ours_warm_pair_peer() {
    return {"trackphys", [](const Ellipsoid& a, const Ellipsoid& b, const glm::dvec3& start) {
                return PairPeerDepth{ellipsoid_ellipsoid_contact(a, b, start).depth, false};
            }};
}

/// The families every comparison runs on (car-like first), `per_family` pairs each from one
/// seed, with their long-double references.
inline std::vector<PairFamily> make_pair_families(int per_family) {
    std::vector<PairFamily> families;
    test::PairCaseGenerator generator(2026);
    for (const test::PairKind kind :
         {test::PairKind::car_like, test::PairKind::grazing, test::PairKind::far,
          test::PairKind::sphere_ellipsoid, test::PairKind::deep, test::PairKind::elongated,
          test::PairKind::crossing, test::PairKind::coincident}) {
        PairFamily family{kind, {}, {}};
        for (int i = 0; i < per_family; ++i) {
            family.cases.push_back(generator.make(kind));
            test::PairReference reference(family.cases.back().a, family.cases.back().b);
            family.reference.push_back(double(reference.solve().depth));
        }
        families.push_back(std::move(family));
    }
    return families;
}

/// Whether a score holds our depth contract on its family: no failure, every error within
/// 1e-9 m (1e-11 relative beyond 100 m).
inline bool holds_contract(const PairScore& s, const PairFamily& family) {
    double largest = 0;
    for (const test::PairCase& c : family.cases)
        largest = std::max({largest, c.a.bounding_radius(), c.b.bounding_radius()});
    return s.failures == 0 && s.max_error <= std::max(1e-9, 1e-11 * largest);
}

/// Runs ours and `peers` on every family; returns the exit code (0 unless an argument is bad).
inline int run_pair_peers(int argc, char** argv, const char* program, std::vector<PairPeer> peers) {
    bool quick = false;
    const char* json = nullptr;
    for (int i = 1; i < argc; ++i) {
        if (std::strcmp(argv[i], "--quick") == 0) {
            quick = true;
        } else if (std::strcmp(argv[i], "--json") == 0 && i + 1 < argc) {
            json = argv[++i];
        } else {
            std::fprintf(stderr, "usage: %s [--quick] [--json FILE]\n", program);
            return 2;
        }
    }
    const int per_family = quick ? 40 : 1000;
    peers.insert(peers.begin(), ours_pair_peer());
    const std::vector<PairFamily> families = make_pair_families(per_family);
    std::printf("%s: %d pairs per family%s\n", program, per_family, quick ? " (--quick)" : "");
    std::printf("%-17s %-26s %12s %12s %14s %9s\n", "family", "method", "median ns", "mean ns",
                "max |err| m", "failures");
    bool contract = true;
    std::vector<std::vector<PairScore>> scores(peers.size());
    for (const PairFamily& family : families)
        for (std::size_t p = 0; p < peers.size(); ++p) {
            const PairScore s = score(peers[p], family);
            scores[p].push_back(s);
            std::printf("%-17s %-26s %12.1f %12.1f %14.3g %9d\n", test::pair_kind_name(family.kind),
                        peers[p].name.c_str(), s.median_ns, s.mean_ns, s.max_error, s.failures);
            if (p == 0 && !holds_contract(s, family)) contract = false;
        }
    for (std::size_t p = 1; p < peers.size(); ++p)
        for (std::size_t f = 0; f < families.size(); ++f)
            if (!scores[p][f].worst.empty())
                std::printf("worst %s on %s: %s\n", peers[p].name.c_str(),
                            test::pair_kind_name(families[f].kind), scores[p][f].worst.c_str());
    const auto verdict = [&](bool ok) { return contract && ok ? "met" : "NOT met"; };
    const double ours = scores[0][0].median_ns;  // car-like
    std::printf("contract (every family within 1e-9 m): %s\n", contract ? "held" : "BROKEN");
    std::printf("target: median <= 150 ns on car-like pairs: %.1f ns: %s\n", ours,
                verdict(ours <= 150.0));
    if (peers.size() > 1) {
        double fastest = INFINITY, most_accurate = INFINITY, our_error = 0;
        for (std::size_t p = 1; p < peers.size(); ++p)
            fastest = std::min(fastest, scores[p][0].median_ns);
        for (std::size_t p = 1; p < peers.size(); ++p) {
            double worst = 0;
            for (const PairScore& s : scores[p])
                worst = std::max(worst, s.failures ? INFINITY : s.max_error);
            most_accurate = std::min(most_accurate, worst);
        }
        for (const PairScore& s : scores[0]) our_error = std::max(our_error, s.max_error);
        std::printf(
            "target: >= 10x faster than the fastest peer here (car-like medians): %.1fx: %s\n",
            fastest / ours, verdict(fastest >= 10.0 * ours));
        std::printf(
            "target: >= 100x more accurate than the most accurate peer here (max error "
            "over every family, a failure counting as infinite): %.3g m vs %.3g m: %s\n",
            our_error, most_accurate, verdict(most_accurate >= 100.0 * our_error));
    }
    if (json) {
        std::FILE* out = std::fopen(json, "w");
        if (!out) {
            std::fprintf(stderr, "%s: cannot write %s\n", program, json);
            return 1;
        }
        std::fprintf(out,
                     "{\"program\": \"%s\", \"pairs_per_family\": %d, \"contract_held\": %s, "
                     "\"rows\": [",
                     program, per_family, contract ? "true" : "false");
        const char* separator = "";
        for (std::size_t p = 0; p < peers.size(); ++p)
            for (std::size_t f = 0; f < families.size(); ++f) {
                const PairScore& s = scores[p][f];
                std::fprintf(out,
                             "%s\n  {\"family\": \"%s\", \"method\": \"%s\", \"median_ns\": %.1f, "
                             "\"mean_ns\": %.1f, \"max_error_m\": %.3g, \"failures\": %d}",
                             separator, test::pair_kind_name(families[f].kind),
                             peers[p].name.c_str(), s.median_ns, s.mean_ns,
                             std::isfinite(s.max_error) ? s.max_error : 1e308, s.failures);
                separator = ",";
            }
        std::fprintf(out, "\n]}\n");
        std::fclose(out);
    }
    return 0;
}

}  // namespace trackphys::peers
