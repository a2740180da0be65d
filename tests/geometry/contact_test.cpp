#include "trackphys/geometry/contact.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <string>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "geometry/contact_kernel.hpp"
#include "support/contact_cases.hpp"
#include "support/contact_reference.hpp"
#include "support/world_contact_reference.hpp"
#include "trackphys/error.hpp"
#include "trackphys/geometry/point_ellipsoid.hpp"

namespace trackphys {
namespace {

using test::ContactCase;
using test::ContactCaseGenerator;
using test::ContactKind;
using test::R;
using test::reference;
using test::Referenced;
using test::V3;

bool finite(const Contact& c) {
    return !std::isnan(c.depth) && std::isfinite(c.normal.x) && std::isfinite(c.normal.y) &&
           std::isfinite(c.normal.z) && std::isfinite(c.point.x) && std::isfinite(c.point.y) &&
           std::isfinite(c.point.z);
}

std::string describe(const ContactCase& c) {
    char buffer[512];
    const Ellipsoid& e = c.ellipsoid;
    const Triangle& t = c.triangle;
    std::snprintf(
        buffer, sizeof buffer,
        "%s: center (%.17g %.17g %.17g) q (%.17g %.17g %.17g %.17g) axes (%.17g %.17g %.17g) "
        "tri (%.17g %.17g %.17g) (%.17g %.17g %.17g) (%.17g %.17g %.17g)",
        test::contact_kind_name(c.kind), e.center().x, e.center().y, e.center().z,
        e.orientation().w, e.orientation().x, e.orientation().y, e.orientation().z, e.semi_axes().x,
        e.semi_axes().y, e.semi_axes().z, t[0].x, t[0].y, t[0].z, t[1].x, t[1].y, t[1].z, t[2].x,
        t[2].y, t[2].z);
    return buffer;
}

struct KindStats {
    long cases = 0, unique = 0;
    double depth_error = 0, angle_error = 0, point_error = 0;
};

constexpr double kEpsilon = std::numeric_limits<double>::epsilon();

/// The largest distance from the ellipsoid's center to a vertex (m).
double reach(const ContactCase& c) {
    double r = 0;
    for (int i = 0; i < 3; ++i) r = std::max(r, glm::distance(c.triangle[i], c.ellipsoid.center()));
    return r;
}

void check_case(const ContactCase& c, KindStats& stats) {
    const Contact got = ellipsoid_triangle_contact(c.ellipsoid, c.triangle);
    ASSERT_TRUE(finite(got)) << describe(c);
    const Referenced ref = reference(c.ellipsoid, c.triangle);
    // The reference is a true minimum: no sampled direction is lower.
    ASSERT_GE(double(ref.contact.sampled_min - ref.contact.depth), -1e-12) << describe(c);
    const double depth_error = std::abs(got.depth - double(ref.contact.depth));
    // The contract (docs/design.md#exactness-promises-and-their-tests), then the accuracy
    // the README reports: 1e-12 m, or, where that is larger, 2 eps times the triangle's reach
    // from the center. The vertices' offsets from the center, where any double computation
    // starts, are only known to eps / 2 of that reach, which lifts the bound above 1e-12 m
    // for the huge family's kilometre-sized triangles alone.
    ASSERT_LE(depth_error, 1e-9) << describe(c) << " got " << got.depth << " want "
                                 << double(ref.contact.depth);
    const double measured = std::max(1e-12, 2.0 * kEpsilon * reach(c));
    ASSERT_LE(depth_error, measured)
        << describe(c) << " got " << got.depth << " want " << double(ref.contact.depth);
    ++stats.cases;
    stats.depth_error = std::max(stats.depth_error, depth_error);
    // Unique: the runner-up is 1e-6 m worse and g curves up by >= 1e-2 m/rad^2 around the
    // minimiser (else no double computation fixes the direction to 1e-6 rad).
    if (ref.contact.runner_up - ref.contact.depth >= 1e-6 && ref.contact.rise >= 5e-11) {
        ++stats.unique;
        const double angle = std::atan2(glm::length(glm::cross(got.normal, ref.normal)),
                                        glm::dot(got.normal, ref.normal));
        ASSERT_LE(angle, 1e-6) << describe(c);
        ASSERT_LE(glm::distance(got.point, ref.point), 1e-6) << describe(c);
        stats.angle_error = std::max(stats.angle_error, angle);
        stats.point_error = std::max(stats.point_error, glm::distance(got.point, ref.point));
    }
}

void print(const std::map<ContactKind, KindStats>& stats) {
    std::printf("kind             cases  unique  max|depth err|  max angle  max point err\n");
    for (const auto& [kind, s] : stats)
        std::printf("%-15s %6ld  %6ld  %13.3g  %9.3g  %13.3g\n", test::contact_kind_name(kind),
                    s.cases, s.unique, s.depth_error, s.angle_error, s.point_error);
}

TEST(Contact, MatchesTheLongDoubleReferenceOnEveryKind) {
    ContactCaseGenerator generator(11);
    std::map<ContactKind, KindStats> stats;
    for (int k = 0; k < 13000; ++k) {
        const ContactCase c = generator.make(static_cast<ContactKind>(k % int(ContactKind::count)));
        check_case(c, stats[c.kind]);
        if (HasFatalFailure()) return;
    }
    print(stats);
}

TEST(Contact, MatchesTheLongDoubleReferenceOnTheHardMix) {
    ContactCaseGenerator generator(12);
    std::map<ContactKind, KindStats> stats;
    for (int k = 0; k < 7000; ++k) {
        const ContactCase c = generator.hard_mix();
        check_case(c, stats[c.kind]);
        if (HasFatalFailure()) return;
    }
    print(stats);
}

/// Axis-aligned ellipsoids and vertices on a coarse grid: exact zeros in the local
/// coordinates (the closed-form branches of the root finders), symmetric configurations
/// with several minimisers, vertices on axes, at the center and on the surface.
TEST(Contact, MatchesTheReferenceOnAxisAlignedGrids) {
    ContactCaseGenerator generator(17);
    const glm::dvec3 shapes[] = {
        {0.15, 0.35, 0.35}, {1.0, 0.5, 2.0}, {0.5, 0.5, 0.5}, {0.3, 0.2, 0.1}};
    const double grid[] = {-0.5, -0.35, -0.15, 0.0, 0.0, 0.1, 0.15, 0.35, 0.5, 1.0};
    KindStats stats;
    for (int k = 0; k < 3000; ++k) {
        const glm::dvec3 axes = shapes[k % 4];
        const Ellipsoid e({0, 0, 0}, glm::dquat(1, 0, 0, 0), axes);
        std::array<glm::dvec3, 3> v;
        for (auto& x : v)
            x = {grid[generator.pick(10)], grid[generator.pick(10)], grid[generator.pick(10)]};
        check_case({e, Triangle(v[0], v[1], v[2]), ContactKind::random}, stats);
        if (HasFatalFailure()) return;
    }
    std::printf("axis-aligned grids: %ld cases, %ld unique, max depth error %.3g m\n", stats.cases,
                stats.unique, stats.depth_error);
}

// Which way the kernel answers a case (its sorted frame, the case's vertex order).
detail::ContactPath kernel_path(const ContactCase& c) {
    detail::LocalTriangle local;
    local.extent = 0.0;
    for (int i = 0; i < 3; ++i) {
        local.q[i] = c.ellipsoid.to_sorted_local(c.triangle[i]);
        local.edge[i] = c.ellipsoid.to_sorted_local(c.triangle[(i + 1) % 3]) - local.q[i];
        local.extent += std::abs(local.q[i].x) + std::abs(local.q[i].y) + std::abs(local.q[i].z);
    }
    return detail::contact_in_sorted_frame(c.ellipsoid.sorted_radii(), local).path;
}

TEST(Contact, ShallowRoadContactsTakeTheCertifiedFaceExit) {
    ContactCaseGenerator generator(13);
    int face = 0;
    int count = 0;
    for (int k = 0; k < 10000; ++k) {
        const ContactCase c = generator.make(ContactKind::road);
        // The certificate holds for depth * h(u) < r_min^2; h <= r_max.
        const glm::dvec3 r = c.ellipsoid.sorted_radii();
        if (ellipsoid_triangle_contact(c.ellipsoid, c.triangle).depth * r.x >= r.z * r.z) continue;
        ++count;
        face += kernel_path(c) == detail::ContactPath::face_certified;
    }
    EXPECT_EQ(face, count);
    EXPECT_GT(count, 7000);
}

// A triangle's corner pressed into the car: the vertex inside is tried before the face, and
// its closest-point certificate answers alone (98% here; the rest are deeper than the
// certificate's reach or have another vertex above it).
TEST(Contact, VertexContactsAreCertifiedByTheirVertex) {
    ContactCaseGenerator generator(21);
    int vertex = 0;
    for (int k = 0; k < 10000; ++k) {
        const ContactCase c = generator.make(ContactKind::vertex, /*overlapping=*/true);
        vertex += kernel_path(c) == detail::ContactPath::vertex_certified;
    }
    EXPECT_GT(vertex, 9500);
}

TEST(Contact, RigidMotionsChangeTheDepthByAtMostANanometre) {
    ContactCaseGenerator generator(14);
    double worst = 0;
    for (int k = 0; k < 20000; ++k) {
        const ContactCase c = generator.any();
        const glm::dquat rotation = generator.rotation();
        const glm::dvec3 shift(generator.uniform(-2e4, 2e4), generator.uniform(-1e3, 1e3),
                               generator.uniform(-2e4, 2e4));
        // Anywhere in a 20 km world.
        const auto move = [&](const glm::dvec3& p) { return rotation * p + shift; };
        const Ellipsoid& e = c.ellipsoid;
        const Ellipsoid moved(move(e.center()), rotation * e.orientation(), e.semi_axes());
        const Triangle t(move(c.triangle[0]), move(c.triangle[1]), move(c.triangle[2]));
        const Contact a = ellipsoid_triangle_contact(e, c.triangle);
        const Contact b = ellipsoid_triangle_contact(moved, t);
        ASSERT_TRUE(finite(b));
        if (c.kind == ContactKind::huge)
            continue;  // 1e6 m triangles: 1e-9 m is below their rounding
        ASSERT_LE(std::abs(a.depth - b.depth), 1e-9) << describe(c);
        worst = std::max(worst, std::abs(a.depth - b.depth));
    }
    std::printf("rigid motions: max depth change %.3g m\n", worst);
}

TEST(Contact, VertexOrderChangesNothing) {
    ContactCaseGenerator generator(15);
    for (int k = 0; k < 20000; ++k) {
        const ContactCase c = generator.any();
        std::array<int, 3> order = {0, 1, 2};
        const Contact first = ellipsoid_triangle_contact(c.ellipsoid, c.triangle);
        while (std::next_permutation(order.begin(), order.end())) {
            const Contact other = ellipsoid_triangle_contact(
                c.ellipsoid,
                Triangle(c.triangle[order[0]], c.triangle[order[1]], c.triangle[order[2]]));
            ASSERT_EQ(first.depth, other.depth) << describe(c);
            ASSERT_EQ(first.normal, other.normal) << describe(c);
            ASSERT_EQ(first.point, other.point) << describe(c);
        }
    }
}

TEST(Contact, InvalidEllipsoidsAreRejectedWithAMessage) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const glm::dquat identity(1, 0, 0, 0);
    for (const glm::dvec3& axes :
         {glm::dvec3(0, 1, 1), glm::dvec3(1, -1, 1), glm::dvec3(1, 1, nan)}) {
        try {
            const Ellipsoid e({0, 0, 0}, identity, axes);
            ADD_FAILURE() << "accepted semi-axes " << axes.x << " " << axes.y << " " << axes.z;
        } catch (const Error& error) {
            EXPECT_NE(std::string(error.what()).find("semi-axis"), std::string::npos)
                << error.what();
        }
    }
    std::string why;
    EXPECT_FALSE(Ellipsoid::make({nan, 0, 0}, identity, {1, 1, 1}, &why).has_value());
    EXPECT_NE(why.find("center"), std::string::npos) << why;
}

TEST(Contact, NoInputMakesNaN) {
    const double inf = std::numeric_limits<double>::infinity();
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double big = std::numeric_limits<double>::max();
    const double tiny = std::numeric_limits<double>::denorm_min();
    ContactCaseGenerator generator(16);
    const std::array<double, 10> scales = {0.0, tiny, 1e-300, 1e-150, 1e-9,
                                           1.0, 1e9,  1e150,  1e300,  big};
    for (int k = 0; k < 20000; ++k) {
        const ContactCase c = generator.any();
        const double s = scales[k % scales.size()];
        const glm::dvec3 o = c.ellipsoid.center();
        const Triangle t(o + s * (c.triangle[0] - o), o + s * (c.triangle[1] - o),
                         s * c.triangle[2]);
        const Contact got = ellipsoid_triangle_contact(c.ellipsoid, t);
        ASSERT_TRUE(finite(got)) << describe(c) << " scale " << s;
        ASSERT_NEAR(glm::length(got.normal), 1.0, 1e-12) << describe(c) << " scale " << s;
    }
    for (const double bad : {inf, -inf, nan}) {
        const Ellipsoid e({0, 0, 0}, glm::dquat(1, 0, 0, 0), {1, 2, 3});
        const Contact got =
            ellipsoid_triangle_contact(e, Triangle({0, 0, 0}, {bad, 0, 0}, {0, 1, 0}));
        EXPECT_TRUE(finite(got));
        EXPECT_EQ(got.depth, -inf);
    }
    // Extreme ellipsoids: huge and tiny radii far from the origin.
    for (const glm::dvec3& axes :
         {glm::dvec3(1e300, 1e-300, 1), glm::dvec3(1e-300), glm::dvec3(1e300)}) {
        const Ellipsoid e({1e300, -1e300, 5}, generator.rotation(), axes);
        for (int k = 0; k < 100; ++k) {
            const Triangle t(e.center() + 1e300 * generator.direction(),
                             e.center() + generator.direction(),
                             glm::dvec3(generator.uniform(-1, 1)));
            ASSERT_TRUE(finite(ellipsoid_triangle_contact(e, t)));
        }
    }
}

// Found by fuzz_contact: with a NaN the lexicographic comparisons that order the vertices
// can form a cycle (here v2 < v0 while v1 compares false both ways with each), and vertex
// ranks counted from them repeated and indexed past the triangle. Every order must still
// reach the -infinity answer.
TEST(Contact, NaNVertexInAnyOrderGivesMinusInfinity) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const Ellipsoid e({0, 0, 0}, glm::dquat(1, 0, 0, 0), {1, 2, 3});
    const std::array<glm::dvec3, 3> v = {glm::dvec3(1, 0, 0), glm::dvec3(nan, 0, 0),
                                         glm::dvec3(0, 0, 0)};
    std::array<int, 3> order = {0, 1, 2};
    do {
        const Triangle t(v[order[0]], v[order[1]], v[order[2]]);
        const Contact got = ellipsoid_triangle_contact(e, t);
        EXPECT_TRUE(finite(got));
        EXPECT_EQ(got.depth, -std::numeric_limits<double>::infinity());
    } while (std::next_permutation(order.begin(), order.end()));
}

// Extreme inputs fuzz_contact found making an infinite depth, a NaN point or a normal 2e-7
// off unit: subnormal radii or offsets beside huge ones, radii beyond 2^299, radii ratios
// of 1e114, subnormal offsets beside 1e-76 m radii.
TEST(Contact, FuzzFoundExtremesStayFinite) {
    struct Case {
        glm::dvec3 center;
        glm::dquat orientation;
        glm::dvec3 semi_axes;
        std::array<glm::dvec3, 3> vertices;
    };
    const std::array<Case, 10> cases = {{
        {{2.4977757818599306e-308, 156842196603.99838, 156842099844.51764},
         glm::dquat(0.5, 0.5, 0.5, 0.5),
         {156842099844.51764, 4.9406564584124654e-323, 3.2285213693142097e-319},
         {glm::dvec3(3.3957684451075383e-51, 1.9168343508855124e+170, 0), glm::dvec3(0),
          glm::dvec3(0)}},
        {{0, 1.8917286909320536e-307, 7.2911220195563975e-304},
         glm::dquat(3.4148698114093743e-96, 6.1912347778923578e-313, 0, 1),
         {7.2911220195563975e-304, 1.7383389519587511e-310, 3770908679.3887939},
         {glm::dvec3(0), glm::dvec3(0), glm::dvec3(0)}},
        {glm::dvec3(4.4759381595361623e-91),
         glm::dquat(0.5, 0.5, 0.5, 0.5),
         {4.4207816532211201e+262, 4.4207816532211711e+262, 4.4207816532211711e+262},
         {glm::dvec3(4.4759381595362021e-91, 7.9050503334599447e-323, 5.7326436886959837e-320),
          glm::dvec3(0), glm::dvec3(0)}},
        {{5.4216917988993756e-312, 6.1264140084314571e-322, 2.0527679361347504e-289},
         glm::dquat(1, 0, 0, 0),
         {1.02932062755738e-84, 3.5295363016240204e+30, 3.5295369653413445e+30},
         {glm::dvec3(1.8913127797327678e-307, 2.1609092952369662e+30, 0), glm::dvec3(0),
          glm::dvec3(0)}},
        {{5.3049894823538372e-315, 2.7161546091976399e-310, 1.657809211691619e-316},
         glm::dquat(1, 0, 0, 0),
         {6.3291261944158812e-76, 1.3980432860952889e-76, 1.3980432860952889e-76},
         {glm::dvec3(1.3980432860952889e-76, 0, 0), glm::dvec3(0), glm::dvec3(0)}},
        {{5.3049894823538372e-315, 2.7161546092098928e-310, 1.657809211691619e-316},
         glm::dquat(0.70710678118654346, 0.70710678118655157, -2.4531075428175575e-20,
                    3.1255763602712741e-49),
         {1.0101878239620334e+87, 1.3980434617985879e-76, 1.3980432860952889e-76},
         {glm::dvec3(1.3980432860952889e-76, 1.3980432860952889e-76, 1.1996589727594304e-71),
          glm::dvec3(8.064444989222878e+87, 5.4218226102592659e-312, 8.9003575106947373e-308),
          glm::dvec3(0)}},
        {{5.3049894823538372e-315, 4.9406564584124654e-324, 2.7161546091976399e-310},
         glm::dquat(0, 1.4996965992373291e-241, 1, 3.8359522688441898e-165),
         {1.3980430386505869e-76, 1.3980432860952889e-76, 1.3980432860952889e-76},
         {glm::dvec3(1.1996589727594304e-71, 1.1063139132779746e-47, 4.8925718272660245e-283),
          glm::dvec3(2.117899457122876e-314, 7.2911220466653098e-304, 0), glm::dvec3(0)}},
        {{7.5560014310154563e+78, 7.5560015138364125e+78, 7.5560014310154563e+78},
         glm::dquat(1, 0, 0, 0),
         {7.5560014310154563e+78, 7.55573287026161e+78, 7.5569060567126228e+78},
         {glm::dvec3(-1.5862587963175458e-61, 7.5469551740439473e+78, 7.5560014310154563e+78),
          glm::dvec3(7.5560014310154563e+78, 3.2452779034740585e+88, 7.5560014310154563e+78),
          glm::dvec3(2.7776142677835984e-309, 0, 0)}},
        {{7.0651114597135147e-304, 1.668805393880401e-308, 8.4742139574690607e-320},
         glm::dquat(3.0551530542826517e-253, 1.5822739364005226e-256, 0.70710678115353565,
                    0.7071067812195595),
         glm::dvec3(3.2186704024134878e-57),
         {glm::dvec3(131059.26274509804, 32.501960784246037, 33.806648284313724),
          glm::dvec3(-3.4030000619567244e-161, 0, 0), glm::dvec3(0)}},
        {{5.7840552864802584e+170, -1.797692724301187e+308, 5.8536405370189899e+170},
         glm::dquat(1, 0, 0, 0),
         {2.9357886262539132e-307, 1.740700265154975e-315, 5.8536377117013575e+170},
         {glm::dvec3(1.8456128521100186e-317, -5.4861240892339001e+303, 0), glm::dvec3(0),
          glm::dvec3(0)}},
    }};
    for (const Case& c : cases) {
        const Ellipsoid e(c.center, c.orientation, c.semi_axes);
        const Contact got =
            ellipsoid_triangle_contact(e, Triangle(c.vertices[0], c.vertices[1], c.vertices[2]));
        EXPECT_TRUE(finite(got)) << got.depth;
        EXPECT_TRUE(std::isfinite(got.depth));
        EXPECT_NEAR(glm::length(got.normal), 1.0, 1e-12);
    }
}

/// Checks a configuration whose separation is beyond double's range: the depth saturates
/// at -DBL_MAX, and the normal and the point (the midpoint, within range) match the
/// long-double reference.
void expect_saturated_separation(const Ellipsoid& e, const Triangle& t) {
    const Contact got = ellipsoid_triangle_contact(e, t);
    ASSERT_TRUE(finite(got));
    const Referenced ref = reference(e, t);
    const double largest = std::numeric_limits<double>::max();
    ASSERT_LT(ref.contact.depth, -R(largest));
    EXPECT_EQ(got.depth, -largest);
    EXPECT_LE(glm::distance(got.normal, ref.normal), 1e-15);
    EXPECT_LE(glm::distance(got.point, ref.point), 1e-15 * glm::length(ref.point));
}

// Found by fuzz_contact (fuzz/seeds/fuzz_contact/separation_beyond_double_range.seed): a
// center near -1.6e308 m in x and z and a triangle near 0 there are 2.2e308 m apart, and
// the depth came back -infinity with the point (inf, -inf, inf). The ellipsoid (1e-250 m)
// acts as a point there; the quaternion's norm overflows, so the orientation is the
// identity (Ellipsoid's documented fallback). The second case takes the unit-scale solver.
TEST(Contact, SeparationBeyondDoubleRangeSaturates) {
    expect_saturated_separation(
        Ellipsoid({-0x1.c306969697777p+1023, 0x1.000000000ffffp+659, -0x1.c306969696d69p+1023},
                  glm::dquat(0x1.000000000ffffp-1021, -0x1.0150000000021p-175,
                             0x1.5000000309b95p+666, 0x1.9696d69696969p+663),
                  {0x0.0515101696969p-1022, 0x1.c0c0c69696901p-831, 0x1.151510c0c0c0cp-890}),
        Triangle({0x1p+273, 0x1.f515171515151p-624, -0x1.7777777777777p+456},
                 {-0x1.0c400ffd3ff77p+561, 0x0.0002100e3e3e3p-1022, 0x1.09b95b5001500p-1020},
                 {-0x1.3e3e3e3e3e300p+575, -0x1.cfdffff0cfde3p+1009, 0}));
    expect_saturated_separation(
        Ellipsoid({-1.7e308, 1e300, 0}, glm::dquat(1, 0, 0, 0), {1e307, 2e306, 3e306}),
        Triangle({1.7e308, 0, 0}, {1.6e308, 1e307, 0}, {1.6e308, 0, 1e307}));
}

Ellipsoid scaled(double s, const Ellipsoid& e) {
    return Ellipsoid(s * e.center(), e.orientation(), s * e.semi_axes());
}

Triangle scaled(double s, const Triangle& t) { return Triangle(s * t[0], s * t[1], s * t[2]); }

// Issue 8: fuzz_contact found normals 0.987 long (semi-axes ~6e257 beside a vertex at
// -3.5e296) and 4.3e-9 off unit (coordinates ~1e209, radii ~1e170). The rescaled path
// brought the world's largest coordinate near 1 but left the ellipsoid and the triangle's
// offsets from its center near 1e-39 of it. The kernel's answer scales with the input: a
// power-of-two scale s is exact on every input, so contact(s E, s T) = s contact(E, T) to
// the contract (1e-9 of s), from radii of 1e-150 m to 1e300 m.
TEST(Contact, PowerOfTwoScalesScaleTheContact) {
    ContactCaseGenerator generator(19);
    for (int k = 0; k < 20000; ++k) {
        const ContactCase c = generator.any();
        const Contact base = ellipsoid_triangle_contact(c.ellipsoid, c.triangle);
        const int exponent = -500 + generator.pick(1495);  // 2^-500 ~ 3e-151 .. 2^994 ~ 2e299
        const double s = std::ldexp(1.0, exponent);
        const Contact got =
            ellipsoid_triangle_contact(scaled(s, c.ellipsoid), scaled(s, c.triangle));
        ASSERT_TRUE(finite(got)) << describe(c) << " scale 2^" << exponent;
        ASSERT_NEAR(glm::length(got.normal), 1.0, 1e-12) << describe(c) << " scale 2^" << exponent;
        ASSERT_NEAR(got.depth / s, base.depth, 1e-9) << describe(c) << " scale 2^" << exponent;
    }
}

// The same far from the origin: an ellipsoid of radii from 1e-150 m to 1e300 m (each axis
// on its own, so ratios up to 1e450 are raised as the kernel documents) at up to 1e300 m
// from the origin, its triangle's vertices within a few of its radii, or far out.
TEST(Contact, HugeAndTinyScalesFarOutKeepAUnitNormal) {
    ContactCaseGenerator generator(20);
    const auto power = [&](double lo, double hi) {
        return std::pow(10.0, generator.uniform(lo, hi));
    };
    // The two findings of issue 8, as closely as the lost reports describe them.
    const std::array<std::pair<Ellipsoid, Triangle>, 2> findings = {{
        {Ellipsoid({1e296, -2e296, 3e295}, generator.rotation(), {6e257, 5.9e257, 6.1e257}),
         Triangle({-3.5e296, 1e296, 2e295}, {1e296, -2e296, 3e295 + 5e257},
                  {1e296 + 4e257, -2e296, 3e295})},
        {Ellipsoid({1e209, 2e209, -3e209}, generator.rotation(), {1e170, 2e170, 3e170}),
         Triangle({1e209 + 1e170, 2e209, -3e209}, {1e209, 2e209 + 2e170, -3e209},
                  {1e209, 2e209, -3e209 + 4e170})},
    }};
    for (const auto& [e, t] : findings) {
        const Contact got = ellipsoid_triangle_contact(e, t);
        ASSERT_TRUE(finite(got));
        ASSERT_NEAR(glm::length(got.normal), 1.0, 1e-12);
    }
    for (int k = 0; k < 20000; ++k) {
        const glm::dvec3 radii(power(-150, 300), power(-150, 300), power(-150, 300));
        const glm::dvec3 center = power(-10, 300) * generator.direction();
        const Ellipsoid e(center, generator.rotation(), radii);
        const double reach = std::max({radii.x, radii.y, radii.z});
        std::array<glm::dvec3, 3> v;
        for (glm::dvec3& x : v)
            x = generator.pick(8) == 0
                    ? power(-10, 300) * generator.direction()
                    : center + reach * generator.uniform(0, 3) * generator.direction();
        const Triangle t(v[0], v[1], v[2]);
        const Contact got = ellipsoid_triangle_contact(e, t);
        ASSERT_TRUE(finite(got)) << k;
        ASSERT_TRUE(std::isfinite(got.depth)) << k;
        ASSERT_NEAR(glm::length(got.normal), 1.0, 1e-12)
            << "radii " << radii.x << " " << radii.y << " " << radii.z << " center " << center.x
            << " " << center.y << " " << center.z << " v " << v[0].x << " " << v[1].x << " "
            << v[2].x;
    }
}

// Found by fuzz_contact: a center 1e-311 m (subnormal) off a triangle vertex made the solver
// miss the minimum by 1.3 cm; the depth must match the same ellipsoid rebuilt from its
// sorted axes, and the exact answer, the smallest radius (the triangle lies on one side of
// that axis through the vertex at the center).
TEST(Contact, SubnormalOffsetKeepsTheDepth) {
    const glm::dquat q(3.3236003152765345e-21, 0.99643207332977257, 0.084398597380115195,
                       2.0678640065606455e-309);
    const Ellipsoid e({1.0848620590898777e-311, 0, 1.2670728489188315e-279}, q,
                      {32, 32.501960784313724, 32.501960784313724});
    const Ellipsoid sorted(e.center(), glm::quat_cast(e.sorted_axes()), e.sorted_radii());
    const double s = 32.501960784313724;
    const Triangle t({s, s, s}, {s, 0, 0}, {0, 0, 0});
    EXPECT_NEAR(ellipsoid_triangle_contact(e, t).depth, 32.0, 1e-9);
    EXPECT_NEAR(ellipsoid_triangle_contact(sorted, t).depth, 32.0, 1e-9);
}

// Found by fuzz_contact: collinear vertices under a flat ellipsoid certified a face whose
// normal was rounding noise, 1.4e-4 m off; the segment's true separation is 0.877095 m
// (checked by sampling the point-ellipsoid distance along it).
TEST(Contact, CollinearTriangleIsNotCertifiedAsAFace) {
    const Ellipsoid e({10.99609375, 0, 0.87890625},
                      glm::dquat(0.0023343212240219168, 0, 0, -0.99999727546849992),
                      {29.3662109375, 29.3662109375, 0.001953125});
    const Triangle t({-107.4609375, 0, 0}, {-0.96875, 0, 0}, {0, 0, 0});
    double separation = std::numeric_limits<double>::infinity();
    for (int i = 0; i <= 20000; ++i) {
        const glm::dvec3 p(-0.96875 * i / 20000.0, 0, 0);  // the part under the ellipsoid
        separation = std::min(separation, closest_point_on_ellipsoid(e, p).distance);
    }
    EXPECT_NEAR(ellipsoid_triangle_contact(e, t).depth, -separation, 1e-9);
}

TEST(Contact, KnownAnswers) {
    const glm::dquat identity(1, 0, 0, 0);
    // A unit sphere 0.9 above the plane y = 0: depth 0.1 upwards, point halfway into it.
    const Ellipsoid sphere({0, 0.9, 0}, identity, {1, 1, 1});
    const Contact road =
        ellipsoid_triangle_contact(sphere, Triangle({-5, 0, -5}, {0, 0, 5}, {5, 0, -5}));
    EXPECT_NEAR(road.depth, 0.1, 1e-15);
    EXPECT_NEAR(glm::distance(road.normal, glm::dvec3(0, 1, 0)), 0.0, 1e-15);
    EXPECT_NEAR(glm::distance(road.point, glm::dvec3(0, -0.05, 0)), 0.0, 1e-15);
    // The wheel resting on its rim (radius 0.35) 2 cm into the road, axle along x.
    const Ellipsoid wheel({0, 0.33, 0}, identity, {0.15, 0.35, 0.35});
    EXPECT_NEAR(
        ellipsoid_triangle_contact(wheel, Triangle({-5, 0, -5}, {0, 0, 5}, {5, 0, -5})).depth, 0.02,
        1e-15);
    // A sphere 2 m above a vertex: apart by 1 m, pushed straight up.
    const Ellipsoid high({0, 2, 0}, identity, {1, 1, 1});
    const Contact apart =
        ellipsoid_triangle_contact(high, Triangle({0, 0, 0}, {1, -1, 0}, {-1, -1, 0.5}));
    EXPECT_NEAR(apart.depth, -1.0, 1e-15);
    EXPECT_NEAR(glm::distance(apart.normal, glm::dvec3(0, 1, 0)), 0.0, 1e-15);
    EXPECT_NEAR(glm::distance(apart.point, glm::dvec3(0, 0.5, 0)), 0.0, 1e-15);
}

}  // namespace
}  // namespace trackphys
