// The mid phase's look-ahead: a query for several steps holds every triangle of the steps
// it covers, a list is reused exactly while the steps stay inside its shape, and an empty
// list looks to the end of the update.
#include "trackphys/collision/look_ahead_list.hpp"

#include <algorithm>
#include <memory>
#include <vector>

#include <gtest/gtest.h>

#include "trackphys/collision/static_world.hpp"

namespace trackphys {
namespace {

constexpr double kStepDt = 0.001;  // s
constexpr double kSlack = 0.005;   // m
const glm::dvec3 kWheel(0.15, 0.35, 0.35);

// A flat ground of 0.5 m squares over [-20, 20] m in x and z, at y = 0.
std::shared_ptr<const StaticWorld> ground() {
    TriangleMesh mesh;
    constexpr int kCells = 80;
    for (int i = 0; i <= kCells; ++i)
        for (int k = 0; k <= kCells; ++k)
            mesh.vertices.push_back({-20.0 + 0.5 * i, 0.0, -20.0 + 0.5 * k});
    const auto at = [](int i, int k) { return std::uint32_t(i * (kCells + 1) + k); };
    for (int i = 0; i < kCells; ++i)
        for (int k = 0; k < kCells; ++k) {
            mesh.triangles.push_back({at(i, k), at(i, k + 1), at(i + 1, k)});
            mesh.triangles.push_back({at(i + 1, k), at(i, k + 1), at(i + 1, k + 1)});
        }
    auto world = std::make_shared<StaticWorld>();
    world->add(std::make_shared<const StaticCollider>(mesh));
    return world;
}

// The wheel rolling along +x at `speed` (m/s), 1 cm into the ground, after `steps` steps.
SweptEllipsoid wheel_step(double speed, int steps, double height = 0.34) {
    const Ellipsoid wheel(glm::dvec3(-3.0 + speed * kStepDt * steps, height, 0.0),
                          glm::dquat(1, 0, 0, 0), kWheel);
    return {wheel, wheel.center() + glm::dvec3(speed * kStepDt, 0.0, 0.0), 0.01};
}

std::vector<TriangleRef> refs(const std::vector<MidPhaseCandidate>& candidates) {
    std::vector<TriangleRef> out;
    for (const MidPhaseCandidate& c : candidates) out.push_back(c.ref);
    std::sort(out.begin(), out.end(), [](const TriangleRef& a, const TriangleRef& b) {
        return a.collider != b.collider ? a.collider < b.collider : a.triangle < b.triangle;
    });
    return out;
}

TEST(LookAhead, OneStepIsTheStepItself) {
    const SweptEllipsoid step = wheel_step(278.0, 0);
    const SweptEllipsoid same = look_ahead(step, {278.0, 0.0, 0.0}, kStepDt, 1, kSlack);
    EXPECT_EQ(same.ellipsoid.center(), step.ellipsoid.center());
    EXPECT_EQ(same.end, step.end);
    EXPECT_EQ(same.margin, step.margin);
}

TEST(LookAhead, CoversTheStepsOfAStraightPathAndNoMore) {
    for (const double speed : {0.5, 30.0, 278.0}) {
        const SweptEllipsoid ahead =
            look_ahead(wheel_step(speed, 0), {speed, 0.0, 0.0}, kStepDt, 3, kSlack);
        EXPECT_GT(ahead.margin, wheel_step(speed, 0).margin);
        for (int step = 0; step < 3; ++step)
            EXPECT_TRUE(ahead.contains(wheel_step(speed, step))) << speed;
        // A step beyond (farther than the slack) needs a new query.
        if (speed * kStepDt > kSlack) {
            EXPECT_FALSE(ahead.contains(wheel_step(speed, 4))) << speed;
        }
        // A step that strays by more than the slack (a bump) needs a new query.
        EXPECT_FALSE(ahead.contains(wheel_step(speed, 1, 0.34 + 2.0 * kSlack))) << speed;
    }
}

TEST(LookAheadList, ReusedListsHoldEveryTriangleOfTheStepsTheyCover) {
    const auto world = ground();
    MidPhase mid(MidPhaseMode::precomputed_tree, *world, make_collider_plane_trees(*world));
    Aabb box{{-20, -1, -20}, {20, 2, 20}};
    mid.begin_update(box);
    constexpr double kSpeed = 278.0;
    constexpr int kSteps = 10;
    LookAheadList list;
    int queries = 0;
    for (int step = 0; step < kSteps; ++step) {
        const SweptEllipsoid shape = wheel_step(kSpeed, step);
        if (!list.covers(shape)) {
            const int ahead = list.steps_ahead(3, kSteps - step);
            if (step > 0) {
                EXPECT_EQ(ahead, std::min(3, kSteps - step)) << "a wheel on the ground";
            }
            list.refill(mid, look_ahead(shape, {kSpeed, 0.0, 0.0}, kStepDt, ahead, kSlack));
            ++queries;
        }
        std::vector<MidPhaseCandidate> own;
        mid.query_swept_ellipsoid(shape.ellipsoid, shape.end, shape.margin, own);
        ASSERT_FALSE(own.empty());
        const std::vector<TriangleRef> listed = refs(list.candidates()), needed = refs(own);
        EXPECT_TRUE(std::includes(listed.begin(), listed.end(), needed.begin(), needed.end(),
                                  [](const TriangleRef& a, const TriangleRef& b) {
                                      return a.collider != b.collider ? a.collider < b.collider
                                                                      : a.triangle < b.triangle;
                                  }))
            << "step " << step;
    }
    EXPECT_LE(queries, 5);  // steps 0, 3, 6 and 9 (the first list looks to the end: empty)
    list.forget();
    EXPECT_FALSE(list.covers(wheel_step(kSpeed, 9)));
}

TEST(LookAheadList, AnEmptyListLooksToTheEndOfTheUpdate) {
    const auto world = ground();
    MidPhase mid(MidPhaseMode::precomputed_tree, *world, make_collider_plane_trees(*world));
    mid.begin_update(Aabb{{-20, -1, -20}, {20, 5, 20}});
    LookAheadList list;
    const SweptEllipsoid above = wheel_step(278.0, 0, 2.0);
    list.refill(mid, look_ahead(above, {278.0, 0.0, 0.0}, kStepDt, 3, kSlack));
    EXPECT_TRUE(list.candidates().empty());
    EXPECT_EQ(list.steps_ahead(3, 7), 7);
    EXPECT_EQ(list.steps_ahead(1, 7), 1);  // every step its own query, as asked
    list.refill(mid, wheel_step(278.0, 0));
    EXPECT_FALSE(list.candidates().empty());
    EXPECT_EQ(list.steps_ahead(3, 7), 3);
    EXPECT_EQ(list.steps_ahead(3, 2), 2);
}

}  // namespace
}  // namespace trackphys
