// The ellipsoid-ellipsoid contact against its peers (issue 15): ours, Bullet's GJK/EPA
// (float, the build trackphys-bench links; bench_peers_ellipsoid_pair_bullet_double has the
// double one), FCL's two solvers and MuJoCo's convex collider on the same families of pairs
// (peers/ellipsoid_pair_peer_harness.hpp: 1000 pairs each, 40 with --quick), each pair
// timed over 16 back-to-back calls and its depth checked against the long-double
// reference; the car-like pairs again, started from their contacts a sub-step earlier
// (ours and Bullet); then the batched call (ellipsoid_ellipsoid_contacts) on each family,
// checked bit for bit against the single call; then ellipsoids_may_touch on pairs it
// rejects, by each certificate. Adds the four target lines, each met only while
// ours holds its depth contract on every family (and the rejections only while every
// rejected pair is beyond reach); the warm start's, met only while the warm contacts hold
// it; and the batch's, met only while its contacts are also the single call's.

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <span>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "bench_suite.hpp"
#include "geometry/ellipsoid_pair_kernel.hpp"
#include "peers/ellipsoid_pair_peer_harness.hpp"
#include "support/ellipsoid_pair_cases.hpp"
#include "support/ellipsoid_pair_reference.hpp"
#include "trackphys/geometry/ellipsoid_pair.hpp"

#if TRACKPHYS_HAVE_BULLET
#include "peers/ellipsoid_pair_bullet.hpp"
#endif
#if TRACKPHYS_HAVE_FCL
#include "peers/ellipsoid_pair_fcl.hpp"
#endif
#if TRACKPHYS_HAVE_MUJOCO
#include "peers/ellipsoid_pair_mujoco.hpp"
#endif

namespace trackphys::suite {
namespace {

constexpr const char* kGroup = "pair";
// How far a pair phase looks around each pair (m): ellipsoids_may_touch's reach.
constexpr double kReach = 0.05;

/// Car-like pairs 0.06 to 5 m apart (log-uniform), the pairs a pair phase sees near a car,
/// split by the certificate that rejects them; the rest may touch within kReach.
struct RejectionSets {
    std::vector<test::PairCase> by_spheres, by_gap;
    int kept = 0;
    bool proven = true;  ///< every rejected pair is beyond reach by the long-double reference
};

RejectionSets rejection_sets(int count) {
    test::PairCaseGenerator generator(1515);
    RejectionSets sets;
    for (int i = 0; i < count; ++i) {
        const Ellipsoid b(glm::dvec3(0.0), generator.rotation(), generator.car_axes());
        const double gap = generator.log_uniform(0.06, 5.0);
        const test::PairCase c{
            generator.placed(generator.car_axes(), generator.rotation(), b, -gap), b,
            test::PairKind::car_like};
        if (ellipsoids_may_touch(c.a, c.b, kReach)) {
            ++sets.kept;
            continue;
        }
        test::PairReference reference(c.a, c.b);
        if (!(double(reference.solve().depth) < -kReach)) sets.proven = false;
        const double spheres = c.a.bounding_radius() + c.b.bounding_radius() + kReach;
        (glm::distance(c.a.center(), c.b.center()) > spheres ? sets.by_spheres : sets.by_gap)
            .push_back(c);
    }
    return sets;
}

/// Median time of one rejection over the set, cycled (ns).
double rejection_ns(const std::vector<test::PairCase>& cases, const BenchRun& run) {
    if (cases.empty()) return 0.0;
    std::size_t i = 0;
    return median_call_ns(
        [&] {
            keep(ellipsoids_may_touch(cases[i].a, cases[i].b, kReach));
            i = i + 1 == cases.size() ? 0 : i + 1;
        },
        int(cases.size()), run.batches(21, 101));
}

/// Pairs as the batched call takes them.
struct PairLists {
    std::vector<Ellipsoid> a, b;
    std::vector<double> reference;  ///< the long-double depth of each pair
};

/// The family's pairs; with `unsearched`, only those the single call certifies without its
/// search (the typical pairs, whose time the single call's median measures).
PairLists pair_lists(const peers::PairFamily& family, bool unsearched) {
    PairLists lists;
    for (std::size_t i = 0; i < family.cases.size(); ++i) {
        const test::PairCase& c = family.cases[i];
        const detail::PairPath path = detail::pair_solution(c.a, c.b).path;
        if (unsearched &&
            (path == detail::PairPath::searched || path == detail::PairPath::unproven))
            continue;
        lists.a.push_back(c.a);
        lists.b.push_back(c.b);
        lists.reference.push_back(family.reference[i]);
    }
    return lists;
}

bool same_bits(const Contact& x, const Contact& y) {
    const auto b = [](double v) { return std::bit_cast<std::uint64_t>(v); };
    return b(x.depth) == b(y.depth) && b(x.normal.x) == b(y.normal.x) &&
           b(x.normal.y) == b(y.normal.y) && b(x.normal.z) == b(y.normal.z) &&
           b(x.point.x) == b(y.point.x) && b(x.point.y) == b(y.point.y) &&
           b(x.point.z) == b(y.point.z);
}

/// The batched call on a list of pairs: whether every contact is the single call's bit for
/// bit, its depth's largest error against the reference, and the time per pair (the median
/// of repeated passes over the whole list, divided by its length) of one call over the list,
/// of calls of eight pairs (a car pair's worth) and of the single call pair by pair, the three
/// taking turns pass by pass.
struct BatchScore {
    bool same_bits = true;
    double max_error = 0.0, batch_ns = 0.0, eights_ns = 0.0, single_ns = 0.0;
};

BatchScore score_batch(const PairLists& lists, const BenchRun& run) {
    const std::size_t count = lists.a.size();
    std::vector<Contact> contacts(count);
    ellipsoid_ellipsoid_contacts(lists.a, lists.b, contacts);
    BatchScore s;
    for (std::size_t i = 0; i < count; ++i) {
        if (!same_bits(contacts[i], ellipsoid_ellipsoid_contact(lists.a[i], lists.b[i])))
            s.same_bits = false;
        const double error = std::abs(contacts[i].depth - lists.reference[i]);
        s.max_error = std::isnan(error) ? INFINITY : std::max(s.max_error, error);
    }
    const std::span<const Ellipsoid> a(lists.a), b(lists.b);
    const std::span<Contact> out(contacts);
    const std::vector<double> ns = median_call_ns_in_turns(
        {[&] {
             ellipsoid_ellipsoid_contacts(a, b, out);
             keep(contacts.front());
         },
         [&] {
             for (std::size_t start = 0; start < count; start += 8) {
                 const std::size_t n = std::min<std::size_t>(8, count - start);
                 ellipsoid_ellipsoid_contacts(a.subspan(start, n), b.subspan(start, n),
                                              out.subspan(start, n));
             }
             keep(contacts.front());
         },
         [&] {
             for (std::size_t i = 0; i < count; ++i)
                 out[i] = ellipsoid_ellipsoid_contact(a[i], b[i]);
             keep(contacts.front());
         }},
        1, run.batches(5, 21));
    s.batch_ns = ns[0] / double(count);
    s.eights_ns = ns[1] / double(count);
    s.single_ns = ns[2] / double(count);
    return s;
}

/// One call a pair, cycled over the warm family's pairs that the cold call certifies without
/// a search (as a game's sub-step calls it: each pair once, its branches not yet learnt),
/// cold and warm taking turns: the counterparts of the medians over back-to-back calls.
struct CycledTimes {
    double cold_ns = 0.0, warm_ns = 0.0;
    std::size_t pairs = 0;
};

CycledTimes cycled_cold_and_warm(const peers::WarmPairFamily& warm, const BenchRun& run) {
    std::vector<std::size_t> unsearched;
    for (std::size_t i = 0; i < warm.family.cases.size(); ++i) {
        const test::PairCase& c = warm.family.cases[i];
        const detail::PairPath path = detail::pair_solution(c.a, c.b).path;
        if (path != detail::PairPath::searched && path != detail::PairPath::unproven)
            unsearched.push_back(i);
    }
    if (unsearched.empty()) return {};
    const auto pass = [&](bool warm_start) {
        for (const std::size_t i : unsearched) {
            const test::PairCase& c = warm.family.cases[i];
            keep(warm_start ? ellipsoid_ellipsoid_contact(c.a, c.b, warm.starts[i])
                            : ellipsoid_ellipsoid_contact(c.a, c.b));
        }
    };
    const std::vector<double> ns =
        median_call_ns_in_turns({[&] { pass(false); }, [&] { pass(true); }}, 1, run.batches(5, 21));
    const double count = double(unsearched.size());
    return {ns[0] / count, ns[1] / count, unsearched.size()};
}

}  // namespace

void bench_pair_peers(BenchRun& run) {
    std::vector<peers::PairPeer> methods{peers::ours_pair_peer()};
#if TRACKPHYS_HAVE_BULLET
    methods.push_back(peers::bullet_pair_peer());
#else
    not_built(run, kGroup, "Bullet GJK/EPA");
#endif
#if TRACKPHYS_HAVE_FCL
    for (peers::PairPeer& p : peers::fcl_pair_peers()) methods.push_back(std::move(p));
#else
    not_built(run, kGroup, "FCL");
#endif
#if TRACKPHYS_HAVE_MUJOCO
    peers::MujocoPairScene mujoco;
    if (mujoco.loaded()) methods.push_back(peers::mujoco_pair_peer(mujoco));
#else
    not_built(run, kGroup, "MuJoCo");
#endif
    run.progress(kGroup, "families and long-double references");
    const std::vector<peers::PairFamily> families =
        peers::make_pair_families(run.quick() ? 40 : 1000);
    bool contract = true;
    double our_error = 0.0;
    // Per peer: its car-like median and its largest error over every family (a failure
    // counts as infinite).
    std::vector<double> car_like_ns(methods.size()), worst_error(methods.size(), 0.0);
    std::vector<int> failures(methods.size(), 0);
    for (const peers::PairFamily& family : families) {
        const std::string name = test::pair_kind_name(family.kind);
        const std::string ours_name = name + ": trackphys";
        for (std::size_t m = 0; m < methods.size(); ++m) {
            run.progress(kGroup, name + ": " + methods[m].name);
            const peers::PairScore s = peers::score(methods[m], family);
            BenchRow& row =
                run.add(kGroup, name + ": " + methods[m].name, s.median_ns, m ? ours_name : "");
            row.figures = {{"pairs", double(family.cases.size())},
                           {"mean_ns", s.mean_ns},
                           {"p99_ns", s.p99_ns},
                           {"err_max_m", s.max_error},
                           {"failures", double(s.failures)}};
            if (m > 0 && !s.worst.empty()) row.note = "worst " + s.worst;
            if (family.kind == test::PairKind::car_like) car_like_ns[m] = s.median_ns;
            worst_error[m] = std::max(worst_error[m], s.failures ? INFINITY : s.max_error);
            failures[m] += s.failures;
            if (m == 0) {
                contract = contract && peers::holds_contract(s, family);
                our_error = std::max(our_error, s.max_error);
            }
        }
    }

    // The car-like pairs again, each started from its contact one physics sub-step earlier
    // under a relative motion drawn per pair (test::PairCaseGenerator::earlier): ours and
    // Bullet's GJK/EPA given the same start.
    run.progress(kGroup, "car-like, warm: the contacts a sub-step earlier");
    const peers::WarmPairFamily warm = peers::make_warm_pairs(families.front(), 4040);
    std::vector<double> turn = warm.turn;
    std::sort(turn.begin(), turn.end());
    const double turn_median = turn[turn.size() / 2], turn_p90 = turn[turn.size() * 9 / 10];
    std::vector<peers::WarmPairPeer> warm_methods{peers::ours_warm_pair_peer()};
#if TRACKPHYS_HAVE_BULLET
    warm_methods.push_back(peers::bullet_warm_pair_peer());
#endif
    double warm_ns = 0.0, warm_error = 0.0;
    bool warm_contract = true;
    const CycledTimes cycled = cycled_cold_and_warm(warm, run);
    for (std::size_t m = 0; m < warm_methods.size(); ++m) {
        const std::string name = "car-like, warm: " + warm_methods[m].name;
        run.progress(kGroup, name);
        const peers::PairScore s = peers::score(warm_methods[m], warm);
        BenchRow& row = run.add(kGroup, name, s.median_ns,
                                m ? "car-like, warm: trackphys" : "car_like: trackphys");
        row.figures = {{"pairs", double(warm.family.cases.size())},
                       {"err_max_m", s.max_error},
                       {"failures", double(s.failures)},
                       {"turn_median_rad", turn_median},
                       {"turn_p90_rad", turn_p90}};
        if (m == 0) row.figures.push_back({"cycled_ns", cycled.warm_ns});
        if (m > 0 && !s.worst.empty()) row.note = "worst " + s.worst;
        if (m == 0) {
            warm_ns = s.median_ns;
            warm_error = s.max_error;
            warm_contract = peers::holds_contract(s, warm.family);
        }
    }

    // The batch on every family, and on the car-like pairs certified without a search: the
    // mean over a whole family is mostly its few searched pairs, which the single call's
    // median leaves out.
    bool batch_same = true;
    double batch_car_like_ns = 0.0, batch_car_like_whole_ns = 0.0, cycled_car_like_ns = 0.0;
    std::size_t unsearched_car_like = 0;
    for (const peers::PairFamily& family : families) {
        const std::string name = test::pair_kind_name(family.kind);
        for (const bool unsearched : {false, true}) {
            if (unsearched && family.kind != test::PairKind::car_like) continue;
            const std::string pairs = name + (unsearched ? ", unsearched" : "");
            run.progress(kGroup, pairs + ": trackphys batch");
            const PairLists lists = pair_lists(family, unsearched);
            const BatchScore s = score_batch(lists, run);
            batch_same = batch_same && s.same_bits;
            const auto figures = [&](BenchRow& row) {
                row.figures = {{"pairs", double(lists.a.size())},
                               {"err_max_m", s.max_error},
                               {"same_bits", s.same_bits ? 1.0 : 0.0}};
                if (!s.same_bits) row.note = "NOT the single call's bits";
            };
            const std::string single = pairs + ": trackphys one call a pair";
            figures(run.add(kGroup, single, s.single_ns));
            figures(run.add(kGroup, pairs + ": trackphys batch", s.batch_ns, single));
            if (family.kind == test::PairKind::car_like) {
                figures(run.add(kGroup, pairs + ": trackphys batches of 8", s.eights_ns, single));
                (unsearched ? batch_car_like_ns : batch_car_like_whole_ns) = s.batch_ns;
                if (unsearched)
                    cycled_car_like_ns = s.single_ns, unsearched_car_like = lists.a.size();
            }
        }
    }

    run.progress(kGroup, "rejections and their references");
    const RejectionSets rejections = rejection_sets(run.quick() ? 300 : 3000);
    const double spheres_ns = rejection_ns(rejections.by_spheres, run);
    const double gap_ns = rejection_ns(rejections.by_gap, run);
    const double considered =
        double(rejections.by_spheres.size() + rejections.by_gap.size()) + rejections.kept;
    run.add(kGroup, "may_touch: rejected by the bounding spheres", spheres_ns).figures = {
        {"pairs", double(rejections.by_spheres.size())},
        {"share_pct", 100.0 * double(rejections.by_spheres.size()) / considered}};
    run.add(kGroup, "may_touch: rejected by the centre-line gap", gap_ns).figures = {
        {"pairs", double(rejections.by_gap.size())},
        {"share_pct", 100.0 * double(rejections.by_gap.size()) / considered},
        {"kept_pct", 100.0 * rejections.kept / considered}};

    char evidence[320];
    std::snprintf(evidence, sizeof evidence,
                  "ours: err_max %.2g m over %zu families of %zu pairs, %d failures", our_error,
                  families.size(), families.front().cases.size(), failures[0]);
    std::string peer_failures = "; peers' failures:";
    for (std::size_t m = 1; m < methods.size(); ++m)
        peer_failures += (m > 1 ? ", " : " ") + methods[m].name + " " + std::to_string(failures[m]);
    const std::string pair_evidence =
        evidence + (methods.size() > 1 ? peer_failures : std::string());
    // The 150 ns on car-like pairs, for the single call, the warm start and the batch.
    const auto add_150_ns_line = [&run](const std::string& pairs, const std::string& measure,
                                        double ns, bool held, const std::string& why) {
        run.add_target("ellipsoid pair, " + pairs + ": 150 ns / our " + measure + " (" +
                           std::to_string(int(std::lround(ns))) + " ns)",
                       150.0 / ns, 1.0, held, why);
    };
    const double ours_ns = car_like_ns[0];
    // The median times each pair over back-to-back calls, whose branches the CPU learns; one
    // call a pair over a list of them, as a game's sub-step makes, is beside it.
    std::snprintf(evidence, sizeof evidence,
                  "; one call a pair cycled over the %zu pairs certified without a search: "
                  "%.0f ns a pair",
                  unsearched_car_like, cycled_car_like_ns);
    add_150_ns_line("car-like", "median", ours_ns, contract, pair_evidence + evidence);
    std::snprintf(evidence, sizeof evidence,
                  "warm: err_max %.2g m over %zu car-like pairs; the minimiser turns %.2g rad "
                  "(median), %.2g (90th percentile) in a sub-step; one call a pair cycled over "
                  "the %zu certified without a search: warm %.0f ns, cold %.0f ns",
                  warm_error, warm.family.cases.size(), turn_median, turn_p90, cycled.pairs,
                  cycled.warm_ns, cycled.cold_ns);
    add_150_ns_line("car-like, warm start", "median", warm_ns, warm_contract, evidence);
    std::snprintf(evidence, sizeof evidence,
                  "; car-like pairs certified without a search (the whole family, searches "
                  "included: %.0f ns); the batch's contacts %s the single call's",
                  batch_car_like_whole_ns, batch_same ? "are" : "are NOT");
    add_150_ns_line("car-like certified without a search, batched", "mean time a pair",
                    batch_car_like_ns, contract && batch_same, pair_evidence + evidence);
    const double slower_rejection = std::max(spheres_ns, gap_ns);
    std::snprintf(evidence, sizeof evidence, "spheres %.1f ns, gap %.1f ns; %zu rejected pairs, %s",
                  spheres_ns, gap_ns, rejections.by_spheres.size() + rejections.by_gap.size(),
                  rejections.proven ? "every one beyond reach by the reference"
                                    : "ONE WITHIN REACH by the reference");
    run.add_target(
        "ellipsoid pair rejection: 20 ns / the slower certificate's median",
        20.0 / slower_rejection, 1.0,
        rejections.proven && !rejections.by_spheres.empty() && !rejections.by_gap.empty(),
        evidence);
    if (methods.size() > 1) {
        std::size_t fastest = 1, most_accurate = 1;
        for (std::size_t m = 2; m < methods.size(); ++m) {
            if (car_like_ns[m] < car_like_ns[fastest]) fastest = m;
            if (worst_error[m] < worst_error[most_accurate]) most_accurate = m;
        }
        run.add_target(
            "ellipsoid pair, car-like: fastest peer's time / ours (" + methods[fastest].name + ")",
            car_like_ns[fastest] / ours_ns, 10.0, contract, pair_evidence);
        // Our errors are ~1e-15 m or exactly 0: a floor of 1e-15 m keeps the ratio finite. A
        // peer that failed on any pair has an infinite error: when every peer has, no peer
        // answered every pair, and there is no accuracy to compare.
        run.add_target("ellipsoid pair: most accurate peer's max error / ours (" +
                           methods[most_accurate].name + ")",
                       worst_error[most_accurate] / std::max(our_error, 1e-15), 100.0,
                       contract && std::isfinite(worst_error[most_accurate]), pair_evidence);
    }
}

}  // namespace trackphys::suite
