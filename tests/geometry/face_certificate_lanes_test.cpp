#include "geometry/face_certificate_lanes.hpp"

#include <cstddef>
#include <cstring>
#include <limits>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include <gtest/gtest.h>

#include "core/cpu_features.hpp"
#include "support/contact_cases.hpp"
#include "trackphys/geometry/face_certificate.hpp"
#include "trackphys/geometry/triangle.hpp"

namespace trackphys {
namespace {

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// Both refuse, or both certify with the same bits in every value.
::testing::AssertionResult same_answer(bool certified, const ContactWithSupport& lanes,
                                       const std::optional<ContactWithSupport>& scalar) {
    if (certified != scalar.has_value())
        return ::testing::AssertionFailure()
               << (scalar ? "the lanes refuse what the scalar certifies"
                          : "the lanes certify what the scalar refuses");
    if (!scalar) return ::testing::AssertionSuccess();
    const double got[] = {lanes.depth,   lanes.normal.x, lanes.normal.y, lanes.normal.z,
                          lanes.point.x, lanes.point.y,  lanes.point.z,  lanes.support};
    const double want[] = {scalar->depth,   scalar->normal.x, scalar->normal.y, scalar->normal.z,
                           scalar->point.x, scalar->point.y,  scalar->point.z,  scalar->support};
    for (std::size_t j = 0; j < std::size(got); ++j)
        if (!same_bits(got[j], want[j]))
            return ::testing::AssertionFailure()
                   << "value " << j << ": " << got[j] << " against " << want[j];
    return ::testing::AssertionSuccess();
}

// The certificates of a list of pairs, as World's exact phase runs them.
using Certify = void (*)(std::span<const NormalizedTriangle* const>,
                         std::span<const Ellipsoid* const>, ContactWithSupport*, bool*);

#if defined(__x86_64__) || defined(__i386__)
constexpr Certify kFourLanes = detail::certify_faces_avx2;
#endif
constexpr Certify kTwoLanes = detail::certify_faces_two_lanes;

// Lanes are the scalar certificate bit for bit, each pair in every lane beside others, on
// every kind of case (certified and refused, from above and below the plane), at every list
// length up to three blocks of four: whole blocks and every tail, which repeats its last
// pair in the lanes left over.
void expect_lanes_give_the_scalar_certificate(Certify certify, std::uint64_t seed) {
    test::ContactCaseGenerator cases(seed);
    constexpr int kKinds = static_cast<int>(test::ContactKind::count);
    int certified = 0, refused = 0;
    std::vector<Ellipsoid> ellipsoids;
    std::vector<NormalizedTriangle> frames;
    for (int i = 0; i < 40000; ++i) {
        const test::ContactCase c = cases.make(static_cast<test::ContactKind>(i % kKinds));
        if (c.triangle.is_degenerate()) continue;
        ellipsoids.push_back(c.ellipsoid);
        frames.emplace_back(c.triangle);
        const std::size_t length = static_cast<std::size_t>(i) % 13;
        if (frames.size() < length) continue;
        std::vector<const NormalizedTriangle*> t;
        std::vector<const Ellipsoid*> e;
        for (std::size_t k = 0; k < frames.size(); ++k) {
            t.push_back(&frames[k]);
            e.push_back(&ellipsoids[k]);
        }
        std::vector<ContactWithSupport> got(t.size());
        std::unique_ptr<bool[]> holds(new bool[t.size()]);
        certify(t, e, got.data(), holds.get());
        for (std::size_t k = 0; k < t.size(); ++k) {
            const std::optional<ContactWithSupport> scalar =
                certified_face_contact(frames[k], ellipsoids[k]);
            ASSERT_TRUE(same_answer(holds[k], got[k], scalar))
                << "case " << i << ", pair " << k << " of " << t.size();
            (scalar ? certified : refused) += 1;
        }
        frames.clear();
        ellipsoids.clear();
    }
    EXPECT_GT(certified, 5000);
    EXPECT_GT(refused, 5000);
}

// A pair the certificate holds for (an ellipsoid sunk 5 cm into the face of a flat
// triangle), scaled by `scale`, from above the plane or below it.
struct Pair {
    NormalizedTriangle frame;
    Ellipsoid ellipsoid;
};
Pair sunk_pair(double scale, double side = 1.0) {
    const Triangle t(glm::dvec3(0.0), glm::dvec3(4.0, 0.0, 0.0) * scale,
                     glm::dvec3(1.0, 3.0, 0.0) * scale);
    return {NormalizedTriangle(t),
            Ellipsoid(glm::dvec3(1.5, 1.0, 0.25 * side) * scale, glm::dquat(1, 0, 0, 0),
                      glm::dvec3(0.5, 0.4, 0.3) * scale)};
}

// Inputs that the generator never draws: NaN and infinities in the frame (every compare
// with a NaN fails, both ways), a height of -0.0 (which, as z >= 0.0, pushes along +normal),
// and scales from 1e-300 to 1e300 (the certificate holds at the small ones down to where
// the frame's products underflow; the large ones are thin for it, or their frames overflow).
std::vector<Pair> special_pairs() {
    constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
    constexpr double kInf = std::numeric_limits<double>::infinity();
    std::vector<Pair> pairs{sunk_pair(1.0), sunk_pair(1.0, -1.0)};
    const auto with = [&](auto change) {
        Pair p = sunk_pair(1.0);
        change(p.frame);
        pairs.push_back(p);
    };
    with([&](NormalizedTriangle& f) { f.origin.x = kNaN; });
    with([&](NormalizedTriangle& f) { f.normal.z = kNaN; });
    with([&](NormalizedTriangle& f) { f.dir_y.y = kNaN; });
    with([&](NormalizedTriangle& f) { f.y2 = kNaN; });
    with([&](NormalizedTriangle& f) { f.x1 = kInf; });
    with([&](NormalizedTriangle& f) { f.x2 = -kInf; });
    with([&](NormalizedTriangle& f) { f.origin.z = kInf; });
    with([&](NormalizedTriangle& f) { f.origin.z = -kInf; });
    with([&](NormalizedTriangle& f) { f.dir_x.x = kInf; });
    // -0.0 heights: the centre in the plane, its height (-0) * x + (-0) * y + 1 * (-0).
    for (double lift : {0.0, 0.3}) {
        Pair p = sunk_pair(1.0);
        p.frame.normal = glm::dvec3(-0.0, -0.0, 1.0);
        p.ellipsoid = Ellipsoid(glm::dvec3(1.5, 1.0, -0.0), glm::dquat(1, 0, 0, 0),
                                glm::dvec3(0.5, 0.4, 0.3 + lift));
        pairs.push_back(p);
    }
    for (double scale : {1e-300, 1e-150, 1e-80, 1e-40, 1e40, 1e80, 1e150, 1e300})
        for (double side : {1.0, -1.0}) pairs.push_back(sunk_pair(scale, side));
    // A huge ellipsoid on a small triangle and a tiny one on a huge triangle.
    Pair huge = sunk_pair(1.0);
    huge.ellipsoid = Ellipsoid(glm::dvec3(1.5, 1.0, 1e200), glm::dquat(1, 0, 0, 0),
                               glm::dvec3(1e200, 1e200, 1e200));
    pairs.push_back(huge);
    Pair tiny = sunk_pair(1e200);
    tiny.ellipsoid = Ellipsoid(glm::dvec3(1.5e200, 1.0e200, 1e-200), glm::dquat(1, 0, 0, 0),
                               glm::dvec3(3e-200, 2e-200, 2e-200));
    pairs.push_back(tiny);
    return pairs;
}

// Each special pair in every lane and in tails, beside ordinary ones: the table, whole and
// from each of its first four pairs on, certified by the lanes and by the scalar function.
void expect_lanes_certify_special_pairs_as_the_scalar(Certify certify) {
    const std::vector<Pair> pairs = special_pairs();
    int certified = 0;
    for (std::size_t from = 0; from < 4; ++from) {
        std::vector<const NormalizedTriangle*> t;
        std::vector<const Ellipsoid*> e;
        for (std::size_t k = from; k < pairs.size(); ++k) {
            t.push_back(&pairs[k].frame);
            e.push_back(&pairs[k].ellipsoid);
        }
        std::vector<ContactWithSupport> got(t.size());
        std::unique_ptr<bool[]> holds(new bool[t.size()]);
        certify(t, e, got.data(), holds.get());
        for (std::size_t k = 0; k < t.size(); ++k) {
            const std::optional<ContactWithSupport> scalar = certified_face_contact(*t[k], *e[k]);
            EXPECT_TRUE(same_answer(holds[k], got[k], scalar)) << "special pair " << from + k;
            certified += scalar ? 1 : 0;
        }
    }
    EXPECT_GT(certified, 12);  // the plain pairs, at 1 m and at 1e-80 and 1e-40 m too
}

TEST(CertifyFaces, TwoLanesCertifySpecialInputsAsTheScalar) {
    expect_lanes_certify_special_pairs_as_the_scalar(kTwoLanes);
}

#if defined(__x86_64__) || defined(__i386__)
TEST(CertifyFaces, FourLanesCertifySpecialInputsAsTheScalar) {
    if (!detail::cpu_has_avx2()) GTEST_SKIP() << "this CPU has no AVX2: four lanes not tested";
    expect_lanes_certify_special_pairs_as_the_scalar(kFourLanes);
}
#endif

TEST(CertifyFaces, TwoLanesGiveTheScalarCertificateBitForBit) {
    expect_lanes_give_the_scalar_certificate(kTwoLanes, 31415);
}

#if defined(__x86_64__) || defined(__i386__)
TEST(CertifyFaces, FourLanesGiveTheScalarCertificateBitForBit) {
    if (!detail::cpu_has_avx2()) GTEST_SKIP() << "this CPU has no AVX2: four lanes not tested";
    expect_lanes_give_the_scalar_certificate(kFourLanes, 31415);
}
#endif

}  // namespace
}  // namespace trackphys
