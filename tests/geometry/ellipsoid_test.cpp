#include "trackphys/geometry/ellipsoid.hpp"

#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/trigonometric.hpp>

#include "trackphys/detail/body_ellipsoid.hpp"
#include "trackphys/error.hpp"

namespace trackphys {
namespace {

const glm::dquat identity(1.0, 0.0, 0.0, 0.0);

TEST(Ellipsoid, SortsAxesDescendingAndKeepsAProperRotation) {
    std::mt19937_64 rng(99);
    std::uniform_real_distribution<double> radius(0.05, 3.0);
    std::normal_distribution<double> normal;
    for (int i = 0; i < 1000; ++i) {
        const glm::dvec3 axes(radius(rng), radius(rng), radius(rng));
        const glm::dquat q =
            glm::normalize(glm::dquat(normal(rng), normal(rng), normal(rng), normal(rng)));
        const Ellipsoid e({1, 2, 3}, q, axes);
        const glm::dvec3 r = e.sorted_radii();
        ASSERT_GE(r.x, r.y);
        ASSERT_GE(r.y, r.z);
        const glm::dmat3& m = e.sorted_axes();
        ASSERT_NEAR(glm::determinant(m), 1.0, 1e-12);
        // Each sorted axis is the given local axis of that radius, in world space.
        const glm::dmat3 rotation = glm::mat3_cast(q);
        for (int k = 0; k < 3; ++k) {
            int given = 0;
            while (axes[given] != r[k] ||
                   std::abs(std::abs(glm::dot(rotation[given], m[k])) - 1.0) > 1e-12) {
                ++given;
                ASSERT_LT(given, 3) << "sorted axis " << k << " matches no given axis";
            }
        }
        // A surface point of the given ellipsoid is on the sorted one too.
        const glm::dvec3 world = e.center() + rotation * glm::dvec3(0.0, axes.y, 0.0);
        const glm::dvec3 local = e.to_sorted_local(world);
        const double level = glm::dot(local / r, local / r);
        ASSERT_NEAR(level, 1.0, 1e-12);
    }
}

TEST(Ellipsoid, BoundsAreTight) {
    const Ellipsoid e({1, 0, 0}, glm::angleAxis(glm::radians(90.0), glm::dvec3(0, 0, 1)),
                      {2.0, 0.5, 0.25});
    // Rotating 90 degrees about z turns the 2 m x axis into world y.
    EXPECT_NEAR(e.bounds().max.x, 1.5, 1e-12);
    EXPECT_NEAR(e.bounds().max.y, 2.0, 1e-12);
    EXPECT_NEAR(e.bounds().max.z, 0.25, 1e-12);
    EXPECT_NEAR(e.bounds().min.y, -2.0, 1e-12);
    EXPECT_EQ(e.bounding_radius(), 2.0);
}

TEST(Ellipsoid, NormalisesTheOrientation) {
    const Ellipsoid e({0, 0, 0}, glm::dquat(2.0, 0.0, 0.0, 0.0), {1, 2, 3});
    EXPECT_EQ(e.orientation(), identity);
    EXPECT_EQ(e.semi_axes(), glm::dvec3(1, 2, 3));
    EXPECT_EQ(e.sorted_radii(), glm::dvec3(3, 2, 1));
}

TEST(Ellipsoid, TransformedEqualsBuildingTheMovedEllipsoid) {
    std::mt19937_64 rng(7);
    std::normal_distribution<double> normal;
    for (int i = 0; i < 1000; ++i) {
        const glm::dquat local =
            glm::normalize(glm::dquat(normal(rng), normal(rng), normal(rng), normal(rng)));
        const glm::dquat motion =
            glm::normalize(glm::dquat(normal(rng), normal(rng), normal(rng), normal(rng)));
        const glm::dvec3 center(normal(rng), normal(rng), normal(rng));
        const glm::dvec3 translation(normal(rng) * 100.0, normal(rng), normal(rng));
        const glm::dvec3 axes(0.35, 0.15, 0.35);
        const Ellipsoid body(center, local, axes);
        const Ellipsoid moved = body.transformed(motion, translation);
        const Ellipsoid rebuilt(motion * center + translation, motion * local, axes);
        ASSERT_LE(glm::length(moved.center() - rebuilt.center()), 1e-12);
        ASSERT_EQ(moved.sorted_radii(), rebuilt.sorted_radii());
        for (int k = 0; k < 3; ++k)
            ASSERT_LE(glm::length(moved.sorted_axes()[k] - rebuilt.sorted_axes()[k]), 1e-14);
        const glm::dvec3 p(normal(rng), normal(rng), normal(rng));
        ASSERT_LE(glm::length(moved.to_sorted_local(p) - rebuilt.to_sorted_local(p)), 1e-12);
    }
}

// A game's lerped quaternion, halfway through a 90 degree yaw (0.924 long), moves the
// ellipsoid as its unit quaternion does: before, the centre moved 18 cm and the axes grew.
TEST(Ellipsoid, TransformedNormalisesARotationNotOfUnitLength) {
    const Ellipsoid body({0.9, -0.15, 1.45}, identity, {0.15, 0.35, 0.35});
    const glm::dquat yaw = glm::angleAxis(glm::radians(90.0), glm::dvec3(0, 1, 0));
    const glm::dquat lerped = 0.5 * identity + 0.5 * yaw;
    ASSERT_LT(glm::length(lerped), 0.93);
    const glm::dvec3 at(10.0, 1.0, -5.0);
    const Ellipsoid moved = body.transformed(lerped, at);
    const Ellipsoid unit = body.transformed(glm::normalize(lerped), at);
    // Within a few roundings of the unit rotation's (the division and glm::normalize may
    // differ by an ulp); before, the centre was 0.18 m off and the axes 0.92 long.
    EXPECT_LE(glm::length(moved.center() - unit.center()), 1e-14);
    for (int k = 0; k < 3; ++k) {
        EXPECT_NEAR(glm::length(moved.sorted_axes()[k]), 1.0, 1e-14);
        EXPECT_LE(glm::length(moved.sorted_axes()[k] - unit.sorted_axes()[k]), 1e-14);
    }
    EXPECT_NEAR(glm::length(moved.orientation()), 1.0, 1e-14);
}

template <typename T>
bool same_bits(const T& a, const T& b) {
    return std::memcmp(&a, &b, sizeof a) == 0;
}

// Up to `count` copies of `e` turned by random rotations and turned back: the identity's
// bits again, but axes off the coordinate axes by roundings, which placing must multiply as
// glm does.
std::vector<Ellipsoid> turned_back(const Ellipsoid& e, std::size_t count, std::mt19937_64& rng) {
    std::normal_distribution<double> normal;
    std::vector<Ellipsoid> back;
    for (int turned = 0; back.size() < count && turned < 1000; ++turned) {
        const glm::dquat q =
            glm::normalize(glm::dquat(normal(rng), normal(rng), normal(rng), normal(rng)));
        const Ellipsoid there_and_back =
            e.transformed(q, glm::dvec3(0.0)).transformed(glm::conjugate(q), glm::dvec3(0.0));
        if (same_bits(there_and_back.orientation(), identity) &&
            !same_bits(there_and_back.sorted_axes(), e.sorted_axes()))
            back.push_back(there_and_back);
    }
    return back;
}

// Placing copies the rotation's entries into an unrotated ellipsoid rather than multiplying
// by its axes' ones and zeros when no entry is a zero, which glm's sums would sign by other
// rules: every placing must give the bits of glm's products, zeros of either sign included,
// also for an ellipsoid whose orientation has the identity's bits but whose axes do not;
// a BodyEllipsoid's too, which finds the axes once.
TEST(Ellipsoid, PlacingGivesTheBitsOfGlmsProducts) {
    std::mt19937_64 rng(11);
    std::normal_distribution<double> normal;
    std::uniform_int_distribution<int> pick(0, 15);
    // Every order of the radii (ties too), unrotated, and one rotated ellipsoid.
    const std::array<glm::dvec3, 8> axes = {{{0.15, 0.35, 0.35},
                                             {0.35, 0.15, 0.35},
                                             {0.35, 0.35, 0.15},
                                             {0.8, 0.25, 0.6},
                                             {0.25, 0.8, 0.6},
                                             {0.6, 0.25, 0.8},
                                             {0.25, 0.6, 0.8},
                                             {1.0, 1.0, 1.0}}};
    std::vector<Ellipsoid> bodies;
    for (const glm::dvec3& a : axes) bodies.emplace_back(glm::dvec3(0.9, -0.15, 0.0), identity, a);
    bodies.emplace_back(glm::dvec3(0.0, 0.1, -1.7), glm::dquat(0.9, 0.1, -0.2, 0.3), axes[3]);
    for (const Ellipsoid& back : turned_back(bodies[3], 11, rng)) bodies.push_back(back);
    ASSERT_EQ(bodies.size(), 20u) << "turned-back bodies with tilted axes";
    std::vector<detail::BodyEllipsoid> keyed;
    for (const Ellipsoid& body : bodies) keyed.emplace_back(body);
    int copied = 0;
    for (int trial = 0; trial < 4000; ++trial) {
        // Some components zero, of either sign, as a car standing level has.
        const int zeros = trial % 2 ? pick(rng) : 0;
        std::array<double, 4> q;
        for (int c = 0; c < 4; ++c)
            q[c] = zeros >> c & 1 ? (pick(rng) % 2 ? 0.0 : -0.0) : normal(rng);
        if (zeros == 15) q[0] = 1.0;
        const glm::dquat rotation = glm::normalize(glm::dquat(q[0], q[1], q[2], q[3]));
        const glm::dmat3 matrix = glm::mat3_cast(rotation);
        const PlacingRotation placing(rotation);
        copied += placing.entries_finite_nonzero;
        const glm::dvec3 translation(normal(rng) * 100.0, normal(rng), normal(rng));
        for (std::size_t b = 0; b < bodies.size(); ++b) {
            const Ellipsoid& body = bodies[b];
            std::array<Ellipsoid, 2> placed = {body, body};
            body.place_copy(placed[0], placing, translation);
            keyed[b].place_copy(placed[1], placing, translation);
            for (const Ellipsoid& p : placed) {
                ASSERT_TRUE(same_bits(p.center(), matrix * body.center() + translation));
                ASSERT_TRUE(same_bits(p.orientation(), rotation * body.orientation()))
                    << "trial " << trial << ", body " << b;
                ASSERT_TRUE(same_bits(p.sorted_axes(), matrix * body.sorted_axes()))
                    << "trial " << trial << ", body " << b;
                ASSERT_TRUE(same_bits(p.sorted_radii(), body.sorted_radii()));
            }
        }
    }
    EXPECT_GT(copied, 1000);  // the copies were tested, not only the products
}

// A BodyEllipsoid given another ellipsoid must place it by that one's axes, not the ones
// found for the last: an unrotated ellipsoid replaced by a turned-back copy of itself (the
// same orientation bits, tilted axes) is multiplied, and the copy replaced by the unrotated
// one copied, both with glm's bits.
TEST(BodyEllipsoid, PlacesANewEllipsoidByItsOwnAxes) {
    std::mt19937_64 rng(5);
    std::normal_distribution<double> normal;
    const Ellipsoid unrotated(glm::dvec3(0.0, 0.35, 0.0), identity, glm::dvec3(0.75, 0.4, 1.2));
    const std::vector<Ellipsoid> backs = turned_back(unrotated, 8, rng);
    ASSERT_EQ(backs.size(), 8u);
    int tilted_differ = 0;
    for (const Ellipsoid& back : backs) {
        detail::BodyEllipsoid body(unrotated);
        for (const Ellipsoid& now : {back, unrotated}) {
            body = detail::BodyEllipsoid(now);
            for (int trial = 0; trial < 50; ++trial) {
                const glm::dquat rotation =
                    glm::normalize(glm::dquat(normal(rng), normal(rng), normal(rng), normal(rng)));
                const glm::dmat3 matrix = glm::mat3_cast(rotation);
                Ellipsoid placed = now;
                body.place_copy(placed, PlacingRotation(rotation), glm::dvec3(1.0, 2.0, 3.0));
                ASSERT_TRUE(same_bits(placed.orientation(), rotation * now.orientation()));
                ASSERT_TRUE(same_bits(placed.sorted_axes(), matrix * now.sorted_axes()));
                // What the other ellipsoid's axes would give is other bits, so the asserts
                // above tell which axes were used.
                tilted_differ +=
                    !same_bits(matrix * back.sorted_axes(), matrix * unrotated.sorted_axes());
            }
        }
    }
    EXPECT_GT(tilted_differ, 700);
}

TEST(Ellipsoid, RejectsInvalidInputWithAMessage) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double inf = std::numeric_limits<double>::infinity();
    struct Case {
        glm::dvec3 center;
        glm::dquat orientation;
        glm::dvec3 axes;
        const char* expected;
    };
    const Case cases[] = {
        {{0, 0, 0}, identity, {0, 1, 1}, "semi-axis x"},
        {{0, 0, 0}, identity, {1, -1, 1}, "semi-axis y"},
        {{0, 0, 0}, identity, {1, 1, nan}, "semi-axis z"},
        {{0, 0, 0}, identity, {1, inf, 1}, "semi-axis y"},
        {{nan, 0, 0}, identity, {1, 1, 1}, "center"},
        {{0, 0, 0}, glm::dquat(0, 0, 0, 0), {1, 1, 1}, "zero"},
        {{0, 0, 0}, glm::dquat(nan, 0, 0, 0), {1, 1, 1}, "orientation"},
    };
    for (const Case& c : cases) {
        try {
            Ellipsoid(c.center, c.orientation, c.axes);
            ADD_FAILURE() << "accepted an invalid ellipsoid: " << c.expected;
        } catch (const Error& error) {
            EXPECT_NE(std::string(error.what()).find(c.expected), std::string::npos)
                << error.what();
        }
        std::string why;
        EXPECT_FALSE(Ellipsoid::make(c.center, c.orientation, c.axes, &why).has_value());
        EXPECT_NE(why.find(c.expected), std::string::npos) << why;
    }
    EXPECT_TRUE(Ellipsoid::make({0, 0, 0}, identity, {1, 1, 1}).has_value());
}

}  // namespace
}  // namespace trackphys
