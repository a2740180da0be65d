#include "trackphys/geometry/face_certificate.hpp"

#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <random>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

#include "support/contact_cases.hpp"
#include "support/world_contact_reference.hpp"
#include "trackphys/geometry/contact.hpp"
#include "trackphys/geometry/ellipsoid_cull.hpp"

namespace trackphys {
namespace {

double angle_between(const glm::dvec3& a, const glm::dvec3& b) {
    return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b));
}

/// The largest distance from the ellipsoid's center to a vertex (m).
double reach(const Ellipsoid& e, const Triangle& t) {
    double r = 0;
    for (int i = 0; i < 3; ++i) r = std::max(r, glm::distance(t[i], e.center()));
    return r;
}

/// A certified contact against the long-double reference (the contract: depth 1e-9 m,
/// normal 1e-6 rad, point 1e-6 m) and against ellipsoid_triangle_contact, to rounding.
void expect_exact(const Contact& got, const Ellipsoid& e, const Triangle& t) {
    const test::Referenced ref = test::reference(e, t);
    const double want = double(ref.contact.depth);
    ASSERT_LE(std::abs(got.depth - want), 1e-9) << "got " << got.depth << " want " << want;
    // The normal and the point are fixed only where the minimum is unique (as in the
    // kernel's own test): the runner-up well above it, g curving up around it.
    if (ref.contact.runner_up - ref.contact.depth >= 1e-6 && ref.contact.rise >= 5e-11) {
        EXPECT_LE(angle_between(got.normal, ref.normal), 1e-6);
        EXPECT_LE(glm::distance(got.point, ref.point), 1e-6);
    }
    // The kernel forms the normal from vertices rotated about the centre, rounded to eps
    // of their reach: a triangle of height y2 tilts it by that over y2 (a 1e-8 m triangle
    // by 1e-9 rad), and the extreme point moves with it.
    const Contact kernel = ellipsoid_triangle_contact(e, t);
    const double rounding =
        64.0 * std::numeric_limits<double>::epsilon() * (reach(e, t) + e.sorted_radii().x);
    const double tilt = 1e-12 + rounding / NormalizedTriangle(t).y2;
    EXPECT_LE(std::abs(got.depth - kernel.depth), rounding);
    EXPECT_LE(angle_between(got.normal, kernel.normal), tilt);
    EXPECT_LE(glm::distance(got.point, kernel.point), rounding + e.sorted_radii().x * tilt);
}

// Every kind of the kernel's test cases, adversarial ones included: wherever the
// certificate answers, the answer is exact; and it answers for nearly every road contact.
TEST(CertifiedFaceContact, IsExactWhereverItCertifies) {
    test::ContactCaseGenerator cases(2026);
    constexpr int kKinds = static_cast<int>(test::ContactKind::count);
    std::array<int, kKinds> tried{}, certified{};
    for (int i = 0; i < 13000; ++i) {
        const auto kind = static_cast<test::ContactKind>(i % kKinds);
        const test::ContactCase c = cases.make(kind);
        if (c.triangle.is_degenerate()) continue;
        ++tried[static_cast<std::size_t>(kind)];
        const std::optional<Contact> got =
            certified_face_contact(NormalizedTriangle(c.triangle), c.ellipsoid);
        if (!got) continue;
        ++certified[static_cast<std::size_t>(kind)];
        SCOPED_TRACE(testing::Message()
                     << "case " << i << " (" << test::contact_kind_name(kind) << ")");
        expect_exact(*got, c.ellipsoid, c.triangle);
        if (HasFatalFailure()) return;
    }
    const auto share = [&](test::ContactKind k) {
        const auto i = static_cast<std::size_t>(k);
        return double(certified[i]) / tried[i];
    };
    EXPECT_GT(share(test::ContactKind::road), 0.95);
    EXPECT_GT(share(test::ContactKind::miss), 0.3);
    // Edges and vertices touch where the face cannot answer; deep contacts leave its regime.
    EXPECT_LT(share(test::ContactKind::edge), 0.6);
    EXPECT_LT(share(test::ContactKind::vertex), 0.6);
}

// The support it returns is support_extent's along the contact normal, to the bit, on
// either side of the triangle: World bounds the other survivors with it after a new deepest
// contact instead of computing support_extent again.
TEST(CertifiedFaceContact, ReturnsTheSupportAlongItsNormalToTheBit) {
    test::ContactCaseGenerator cases(7);
    constexpr int kKinds = static_cast<int>(test::ContactKind::count);
    int certified = 0, below = 0;
    for (int i = 0; i < 6000; ++i) {
        const test::ContactCase c = cases.make(static_cast<test::ContactKind>(i % kKinds));
        if (c.triangle.is_degenerate()) continue;
        const NormalizedTriangle frame(c.triangle);
        const std::optional<ContactWithSupport> got = certified_face_contact(frame, c.ellipsoid);
        if (!got) continue;
        ++certified;
        below += glm::dot(got->normal, frame.normal) < 0.0;
        ASSERT_EQ(got->support, support_extent(c.ellipsoid, got->normal)) << "case " << i;
    }
    EXPECT_GT(certified, 1000);
    EXPECT_GT(below, 20);
}

/// A wheel (axle along local x) turned by yaw and tilted by camber, its lowest point
/// depth below the plane y = 0, which a triangle of the given size holds around the
/// footprint (rotated by spin).
struct WheelOnRoad {
    Ellipsoid wheel;
    Triangle road;
};

WheelOnRoad wheel_on_road(double yaw, double camber, double depth, double size, double spin) {
    const glm::dquat q =
        glm::angleAxis(yaw, glm::dvec3(0, 1, 0)) * glm::angleAxis(camber, glm::dvec3(0, 0, 1));
    const Ellipsoid at_origin({0, 0, 0}, q, {0.15, 0.35, 0.35});
    const double lowest = support_extent(at_origin, {0, 1, 0});
    const glm::dvec3 center(3.0, lowest - depth, -7.0);
    const Ellipsoid wheel(center, q, {0.15, 0.35, 0.35});
    const glm::dvec3 foot(center.x, 0.0, center.z);
    std::array<glm::dvec3, 3> v;
    for (int i = 0; i < 3; ++i) {
        const double t = spin + 2.0943951023931953 * i;
        v[i] = foot + size * glm::dvec3(std::cos(t), 0.0, -std::sin(t));
    }
    return {wheel, Triangle(v[0], v[1], v[2])};
}

// The contacts World meets most: a wheel standing on a road triangle, shallow, steered and
// cambered, on big and small triangles. All certified, all exact.
TEST(CertifiedFaceContact, CertifiesAWheelStandingOnARoadTriangle) {
    for (const double size : {0.6, 2.0, 25.0})
        for (const double camber : {-0.15, 0.0, 0.05, 0.2})
            for (const double depth : {1e-4, 3e-3, 0.03}) {
                const double yaw = 0.7 * camber + size;
                const WheelOnRoad c = wheel_on_road(yaw, camber, depth, size, 0.3 * size);
                SCOPED_TRACE(testing::Message()
                             << "size " << size << " camber " << camber << " depth " << depth);
                const std::optional<Contact> got =
                    certified_face_contact(NormalizedTriangle(c.road), c.wheel);
                ASSERT_TRUE(got.has_value());
                EXPECT_NEAR(got->depth, depth, 1e-12);
                EXPECT_EQ(got->normal, glm::dvec3(0, 1, 0));
                expect_exact(*got, c.wheel, c.road);
            }
}

// Both sides of the triangle: from below it pushes down (the wheel 1 cm through it).
TEST(CertifiedFaceContact, PushesTowardsTheSideTheCentreIsOn) {
    const WheelOnRoad above = wheel_on_road(0.2, 0.1, 0.01, 3.0, 0.5);
    const Ellipsoid below(2.0 * glm::dvec3(3.0, 0.0, -7.0) - above.wheel.center(),
                          above.wheel.orientation(), above.wheel.semi_axes());
    const std::optional<Contact> got =
        certified_face_contact(NormalizedTriangle(above.road), below);
    ASSERT_TRUE(got.has_value());
    EXPECT_EQ(got->normal, glm::dvec3(0, -1, 0));
    EXPECT_NEAR(got->point.y, 0.005, 1e-12);  // the midpoint of a 1 cm overlap
    expect_exact(*got, below, above.road);
}

// Apart, with the touching point over the triangle: the gap to the plane is the contact.
TEST(CertifiedFaceContact, CertifiesASeparatedWheelAboveTheTriangle) {
    const WheelOnRoad c = wheel_on_road(0.4, 0.1, -2.5, 10.0, 0.0);
    const std::optional<Contact> got = certified_face_contact(NormalizedTriangle(c.road), c.wheel);
    ASSERT_TRUE(got.has_value());
    EXPECT_NEAR(got->depth, -2.5, 1e-12);
    expect_exact(*got, c.wheel, c.road);
}

/// An upright wheel, 2 mm into the plane y = 0, whose footprint lies at `offset` (m) from
/// the edge of a big triangle along z = 0 (> 0: inside).
std::optional<Contact> wheel_beside_an_edge(double offset) {
    const Ellipsoid wheel({0.0, 0.348, -offset}, glm::dquat(1, 0, 0, 0), {0.15, 0.35, 0.35});
    const Triangle road({5, 0, 0}, {-5, 0, 0}, {0, 0, -8});
    return certified_face_contact(NormalizedTriangle(road), wheel);
}

// The touching point on an edge, or beyond it, is the edges' business: refused. Clear of
// the edge by more than the rounding, it is certified.
TEST(CertifiedFaceContact, RefusesATouchingPointOnOrBeyondAnEdge) {
    EXPECT_TRUE(wheel_beside_an_edge(1e-3).has_value());
    EXPECT_FALSE(wheel_beside_an_edge(0.0).has_value());
    EXPECT_FALSE(wheel_beside_an_edge(-1e-3).has_value());
    EXPECT_FALSE(wheel_beside_an_edge(-0.1).has_value());
}

// Far beside the triangle, apart: the face's touching point misses it.
TEST(CertifiedFaceContact, RefusesAWheelFarBesideTheTriangle) {
    const WheelOnRoad c = wheel_on_road(0.0, 0.0, -1.0, 1.0, 0.0);
    const Ellipsoid away(c.wheel.center() + glm::dvec3(20.0, 0.0, 0.0), c.wheel.orientation(),
                         c.wheel.semi_axes());
    EXPECT_FALSE(certified_face_contact(NormalizedTriangle(c.road), away).has_value());
}

// Deeper than r_min^2 / h(n) (0.15^2 / 0.35 = 6.4 cm for the wheel on its tread) the face
// candidate may not be the closest point: refused, even over the middle of a big triangle.
TEST(CertifiedFaceContact, RefusesADeepContact) {
    const WheelOnRoad shallow = wheel_on_road(0.0, 0.0, 0.06, 20.0, 0.0);
    EXPECT_TRUE(
        certified_face_contact(NormalizedTriangle(shallow.road), shallow.wheel).has_value());
    const WheelOnRoad deep = wheel_on_road(0.0, 0.0, 0.07, 20.0, 0.0);
    EXPECT_FALSE(certified_face_contact(NormalizedTriangle(deep.road), deep.wheel).has_value());
}

// A sliver's normal is too inaccurate for the margin: refused, whatever lies under it.
TEST(CertifiedFaceContact, RefusesASliver) {
    const Triangle thin({-5, 0, 0}, {5, 0, 0}, {0, 0, -0.004});
    const Triangle thick({-5, 0, 0}, {5, 0, 0}, {0, 0, -0.02});
    const Ellipsoid over_thick({0.0, 0.348, -0.01}, glm::dquat(1, 0, 0, 0), {0.15, 0.35, 0.35});
    EXPECT_TRUE(certified_face_contact(NormalizedTriangle(thick), over_thick).has_value());
    const Ellipsoid over_thin({0.0, 0.348, -0.002}, glm::dquat(1, 0, 0, 0), {0.15, 0.35, 0.35});
    EXPECT_FALSE(certified_face_contact(NormalizedTriangle(thin), over_thin).has_value());
}

// A thin triangle 100 km long, allowed by the sliver guard: its frame's normal tilts by up
// to ~eps x1 / y2, which far along it moves the answer by more than the contract allows;
// wherever the certificate still answers, the depth holds to 1e-9 m.
TEST(CertifiedFaceContact, StaysExactOnLongThinTriangles) {
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const auto random_rotation = [&] {
        return glm::normalize(
            glm::dquat(2 * unit(rng) - 1, 2 * unit(rng) - 1, 2 * unit(rng) - 1, 2 * unit(rng) - 1));
    };
    constexpr double kLength = 1e5;  // m
    for (int k = 0; k < 2000; ++k) {
        const glm::dquat q = random_rotation();
        const double height = kLength * std::pow(2.0, -10.0 + 2.0 * unit(rng));
        const glm::dvec3 a(0.0), b = q * glm::dvec3(kLength, 0, 0),
                                 c = q * glm::dvec3(kLength * unit(rng), height, 0);
        const Triangle road(a, b, c);
        double u1 = unit(rng), u2 = unit(rng);
        if (u1 + u2 > 1.0) u1 = 1.0 - u1, u2 = 1.0 - u2;
        const glm::dvec3 foot = a + u1 * (b - a) + u2 * (c - a);
        const glm::dvec3 up = glm::normalize(glm::cross(b - a, c - a));
        const Ellipsoid wheel(foot + 0.33 * up, random_rotation(), {0.35, 0.35, 0.15});
        const std::optional<Contact> got = certified_face_contact(NormalizedTriangle(road), wheel);
        if (!got) continue;
        SCOPED_TRACE(testing::Message() << "case " << k);
        ASSERT_LE(std::abs(got->depth - double(test::reference(wheel, road).contact.depth)), 1e-9);
    }
}

}  // namespace
}  // namespace trackphys
