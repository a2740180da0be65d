#include "geometry/face_certificate_lanes.hpp"

#include <cstddef>
#include <cstring>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include <gtest/gtest.h>

#include "core/cpu_features.hpp"
#include "support/contact_cases.hpp"
#include "trackphys/geometry/face_certificate.hpp"

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
