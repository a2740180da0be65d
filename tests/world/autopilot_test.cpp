// The autopilot drives whole laps of the default track, and a car reaches 1000 km/h on a
// long straight and brakes to a stop, all without leaving the road.
#include "trackphys/world/autopilot.hpp"

#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

#include "support/error_message.hpp"
#include "trackphys/track/track.hpp"
#include "trackphys/world/world.hpp"
#include "world/track_world.hpp"
#include "world/world_scenes.hpp"

namespace trackphys {
namespace {

using test::default_track;
using test::make_track_world;
using test::on_start_line;
using test::TrackWorld;

void drive_a_lap(double target_kmh, const TrackWorld& tw = default_track()) {
    const CarSpec spec = CarSpec::default_car();
    World world(tw.statics, WorldSettings{}, tw.trees);
    world.add_car(spec, on_start_line(tw.track));
    AutopilotSettings settings;
    settings.target_speed = target_kmh / 3.6;
    Autopilot pilot(tw.track, spec, settings);

    const double half_width = 0.5 * tw.track.params.width_m;
    double top = 0.0, worst_overshoot = 0.0;
    for (int i = 0; i < 30000 && pilot.laps() < 1; ++i) {
        Car& car = world.car(0);
        car.set_inputs(pilot.drive(car));
        world.update();
        // Within the walls and above the road: every ellipsoid centre stays between the
        // road edges and above the surface of the nearest centreline sample.
        const CenterlineSample& s = tw.track.centerline[pilot.nearest_sample()];
        for (std::size_t e = 0; e < car.ellipsoid_count(); ++e) {
            const glm::dvec3 offset = car.world_ellipsoid(e).center() - s.position;
            ASSERT_LT(std::abs(glm::dot(offset, s.left)), half_width)
                << "ellipsoid " << e << " at " << s.distance << " m";
            ASSERT_GT(glm::dot(offset, s.up), 0.0)
                << "ellipsoid " << e << " below the road at " << s.distance << " m";
        }
        top = std::max(top, car.speed());
        worst_overshoot =
            std::max(worst_overshoot, car.speed() - pilot.planned_speed(pilot.nearest_sample()));
    }
    EXPECT_EQ(pilot.laps(), 1) << "the lap did not finish";
    // It follows the computed profile: never much faster than planned, and fast where it may.
    EXPECT_LT(worst_overshoot, 0.1 * target_kmh / 3.6);
    EXPECT_GT(top, 0.8 * std::min(target_kmh / 3.6, 70.0));
}

TEST(Autopilot, CompletesALapAt300KmH) { drive_a_lap(300.0); }
TEST(Autopilot, CompletesALapAt600KmH) { drive_a_lap(600.0); }
// Seed 6 has a crest taken at over 300 km/h: the profile slows for it instead of flying.
TEST(Autopilot, SlowsForCrests) { drive_a_lap(600.0, make_track_world(6)); }

TEST(Autopilot, PlannedSpeedFallsInTightTurnsAndRespectsTheTarget) {
    const TrackWorld& tw = default_track();
    AutopilotSettings settings;
    settings.target_speed = 600.0 / 3.6;
    const Autopilot pilot(tw.track, CarSpec::default_car(), settings);
    std::size_t tightest = 0;
    double fastest = 0.0;
    for (std::size_t i = 0; i < tw.track.centerline.size(); ++i) {
        if (std::abs(tw.track.centerline[i].curvature) >
            std::abs(tw.track.centerline[tightest].curvature))
            tightest = i;
        fastest = std::max(fastest, pilot.planned_speed(i));
        ASSERT_LE(pilot.planned_speed(i), settings.target_speed);
        ASSERT_GT(pilot.planned_speed(i), 0.0);
    }
    EXPECT_LT(pilot.planned_speed(tightest), 0.5 * fastest);
}

// The window search as it was first written, every index by division: the nearest sample
// within 400 of the last one, scanned outwards, ahead before behind, the first of a tie.
std::size_t nearest_by_division(const Track& track, std::size_t last, const glm::dvec3& p) {
    const std::vector<CenterlineSample>& line = track.centerline;
    const std::size_t n = line.size();
    const auto distance2 = [&](std::size_t i) {
        return glm::dot(line[i].position - p, line[i].position - p);
    };
    std::size_t best = last;
    for (std::size_t k = 1; k <= 400; ++k) {
        const std::size_t ahead = (last + k) % n;
        const std::size_t behind = (last + n - (k % n)) % n;
        if (distance2(ahead) < distance2(best)) best = ahead;
        if (distance2(behind) < distance2(best)) best = behind;
    }
    return best;
}

// locate() finds the sample the first search did, from anywhere: near the last sample, far
// from it, across the start line, on the road, beside it, above it, and halfway between two.
TEST(Autopilot, LocatesTheSampleTheWindowSearchFinds) {
    const TrackWorld& tw = default_track();
    const std::vector<CenterlineSample>& line = tw.track.centerline;
    const std::size_t n = line.size();
    const CarSpec spec = CarSpec::default_car();
    Autopilot pilot(tw.track, spec);
    std::mt19937 random(16);
    std::uniform_int_distribution<std::size_t> any_sample(0, n - 1);
    std::uniform_int_distribution<std::size_t> nearby(0, 900);  // -450 to +450 samples
    std::uniform_real_distribution<double> across(-20.0, 20.0);
    std::uniform_real_distribution<double> up(-2.0, 6.0);
    int moved = 0;
    for (int trial = 0; trial < 20000; ++trial) {
        const std::size_t last = any_sample(random);
        const std::size_t near =
            trial % 4 == 0 ? any_sample(random) : (last + n - 450 + nearby(random)) % n;
        const CenterlineSample& s = line[near];
        RigidBodyState state;
        // Every 8th trial sits exactly halfway between two samples.
        state.position = trial % 8 == 1 ? 0.5 * (s.position + line[(near + 1) % n].position)
                                        : s.position + across(random) * s.left + up(random) * s.up;
        pilot.set_progress({last, 1, true});
        pilot.locate(Car(spec, state));
        ASSERT_EQ(pilot.nearest_sample(), nearest_by_division(tw.track, last, state.position))
            << "trial " << trial << ", last sample " << last;
        moved += pilot.nearest_sample() != last;
    }
    EXPECT_GT(moved, 10000);
}

// The same on centrelines made to trouble the search's skipping: loops shorter than the
// window (each sample reached from both sides), samples repeated (exact ties), a single
// long chord among short ones, coordinates rounded to a 1 m grid (more ties), and a loop
// far from the origin, with cars on samples, between them and far off the line; and a
// hairpin loop (an ellipse 3 m wide), whose far leg comes back to within metres of a car
// as fast as the chords allow.
TEST(Autopilot, LocatesTheSampleTheWindowSearchFindsOnAwkwardCentrelines) {
    const CarSpec spec = CarSpec::default_car();
    std::mt19937 random(23);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    int checked = 0;
    for (const std::size_t n : {3, 7, 64, 801, 1500}) {
        for (int kind = 0; kind < 5; ++kind) {
            Track track;
            const double radius = 20.0 + 0.5 * static_cast<double>(n);
            const glm::dvec3 origin = kind == 3 ? glm::dvec3(3e7, -2e5, 1e8) : glm::dvec3(0.0);
            for (std::size_t i = 0; i < n; ++i) {
                // kind 1: every third sample repeats the one before; kind 2: the first
                // tenth of the loop squeezed into one long chord, on a 1 m grid.
                double angle =
                    2.0 * std::numbers::pi * static_cast<double>(i) / static_cast<double>(n);
                if (kind == 2 && i > 0)
                    angle = 0.6 + (2.0 * std::numbers::pi - 0.6) * angle / (2.0 * std::numbers::pi);
                CenterlineSample sample;
                sample.position =
                    origin + radius * glm::dvec3(std::cos(angle), 0.05 * std::sin(3.0 * angle),
                                                 std::sin(angle));
                if (kind == 2) sample.position = glm::round(sample.position);
                if (kind == 4) sample.position.z *= 3.0 / radius;
                if (kind == 1 && i % 3 == 2) sample.position = track.centerline.back().position;
                sample.distance = radius * angle;
                track.centerline.push_back(sample);
            }
            track.length_m = 2.0 * std::numbers::pi * radius;
            Autopilot pilot(track, spec);
            for (int trial = 0; trial < 400; ++trial) {
                const std::size_t last = static_cast<std::size_t>(trial * 7919) % n;
                const std::size_t near = static_cast<std::size_t>(trial * 104729 + 1) % n;
                const glm::dvec3 a = track.centerline[near].position;
                const glm::dvec3 b = track.centerline[(near + 1) % n].position;
                RigidBodyState state;
                const double off = trial % 5 == 0 ? 3.0 * radius : 2.0;
                state.position = trial % 4 == 0   ? a
                                 : trial % 4 == 1 ? 0.5 * (a + b)
                                                  : a + off * glm::dvec3(unit(random), unit(random),
                                                                         unit(random));
                pilot.set_progress({last, 1, true});
                pilot.locate(Car(spec, state));
                ASSERT_EQ(pilot.nearest_sample(), nearest_by_division(track, last, state.position))
                    << n << " samples, kind " << kind << ", trial " << trial;
                ++checked;
            }
        }
    }
    EXPECT_EQ(checked, 5 * 5 * 400);
}

// Autopilots given one centreline share it instead of copying it, drive as one that keeps
// its own copy, and refuse a centreline they could not drive along.
TEST(Autopilot, SharesACenterlineAndDrivesAsWithItsOwnCopy) {
    const TrackWorld& tw = default_track();
    const CarSpec spec = CarSpec::default_car();
    const SharedCenterline shared =
        std::make_shared<const std::vector<CenterlineSample>>(tw.track.centerline);
    Autopilot own(tw.track, spec);
    Autopilot first(shared, tw.track.length_m, spec);
    const Autopilot second(shared, tw.track.length_m, spec);
    EXPECT_EQ(&first.centerline(), shared.get());
    EXPECT_EQ(&second.centerline(), shared.get());
    EXPECT_EQ(&Autopilot(first).centerline(), shared.get()) << "a copy shares it too";
    EXPECT_NE(&own.centerline(), &tw.track.centerline);
    for (std::size_t i = 0; i < tw.track.centerline.size(); ++i)
        ASSERT_EQ(first.planned_speed(i), own.planned_speed(i)) << "sample " << i;

    World owner(tw.statics, WorldSettings{}, tw.trees);
    World sharer(tw.statics, WorldSettings{}, tw.trees);
    owner.add_car(spec, on_start_line(tw.track));
    sharer.add_car(spec, on_start_line(tw.track));
    for (int update = 0; update < 300; ++update) {
        owner.car(0).set_inputs(own.drive(owner.car(0)));
        sharer.car(0).set_inputs(first.drive(sharer.car(0)));
        owner.update();
        sharer.update();
    }
    EXPECT_GT(owner.car(0).speed(), 15.0) << "it drove";
    EXPECT_EQ(sharer.state_hash(), owner.state_hash());

    const auto refusal = [&](SharedCenterline centerline, double length) {
        return test::error_of([&] { Autopilot(std::move(centerline), length, spec); });
    };
    EXPECT_EQ(refusal(nullptr, 100.0), "Autopilot: the track has no centreline");
    EXPECT_EQ(refusal(std::make_shared<const std::vector<CenterlineSample>>(2), 100.0),
              "Autopilot: the track has no centreline");
    for (const double length : {0.0, -1.0, std::nan(""), std::numeric_limits<double>::infinity()})
        EXPECT_EQ(refusal(shared, length), "Autopilot: the track's length must be finite and > 0")
            << length;
}

// Settings that would plan or steer by a NaN or an infinity are refused, naming the field;
// a car that cannot steer (max_steer_angle 0) is held straight rather than steered by 0 / 0.
TEST(Autopilot, RefusesSettingsItCannotDriveByAndHoldsACarThatCannotSteerStraight) {
    const test::TrackWorld& tw = test::default_track();
    const auto refusal = [&](auto change) {
        AutopilotSettings settings;
        change(settings);
        return test::error_of([&] { Autopilot(tw.track, CarSpec::default_car(), settings); });
    };
    EXPECT_EQ(refusal([](AutopilotSettings&) {}), "(no error)");
    EXPECT_EQ(refusal([](AutopilotSettings& s) {
                  s.target_speed = std::numeric_limits<double>::infinity();
              }),
              "Autopilot: AutopilotSettings.target_speed must be finite and > 0, got inf");
    EXPECT_EQ(refusal([](AutopilotSettings& s) { s.grip_use = 0.0; }),
              "Autopilot: AutopilotSettings.grip_use must be finite and > 0, got 0");
    EXPECT_EQ(refusal([](AutopilotSettings& s) { s.yaw_damping = std::nan(""); }),
              "Autopilot: AutopilotSettings.yaw_damping must be finite and >= 0, got nan");
    EXPECT_EQ(refusal([](AutopilotSettings& s) { s.lookahead_min = -1.0; }),
              "Autopilot: AutopilotSettings.lookahead_min must be finite and >= 0, got -1");
    EXPECT_EQ(refusal([](AutopilotSettings& s) { s.yaw_damping = 0.0; }), "(no error)");

    CarSpec rigid = CarSpec::default_car();
    rigid.max_steer_angle = 0.0;
    World world(tw.statics, WorldSettings{}, tw.trees);
    world.add_car(rigid, on_start_line(tw.track));
    Autopilot pilot(tw.track, rigid);
    const CarInputs inputs = pilot.drive(world.car(0));
    EXPECT_EQ(inputs.steer, 0.0);
    EXPECT_GT(inputs.throttle, 0.0);
}

// A 7 km straight: full throttle to 1000 km/h, then full brakes to a stop, steering only
// to hold the centre line.
TEST(Autopilot, ReachesThousandKmHOnAStraightAndBrakesToAStop) {
    const double width = 14.0;
    World world(test::static_world_of(test::straight_road(7000.0, width, 2.0)));
    RigidBodyState start;
    start.position = {0.0, 0.501, 5.0};
    world.add_car(CarSpec::default_car(), start);
    bool braking = false;
    double top = 0.0;
    for (int i = 0; i < 20000; ++i) {
        Car& car = world.car(0);
        const RigidBodyState& s = car.state();
        const glm::dvec3 forward = s.orientation * glm::dvec3(0.0, 0.0, 1.0);
        const double steer = -0.5 * s.position.x - 2.0 * forward.x;  // back to x = 0, heading +Z
        braking = braking || car.speed() >= 1000.0 / 3.6;
        car.set_inputs({braking ? 0.0 : 1.0, braking ? 1.0 : 0.0, steer});
        world.update();
        top = std::max(top, car.speed());
        ASSERT_LT(std::abs(s.position.x), 0.5 * width) << "left the road at z = " << s.position.z;
        ASSERT_LT(s.position.z, 7000.0) << "ran off the end of the straight";
        if (braking && car.speed() < 0.1) break;
    }
    EXPECT_GE(top, 1000.0 / 3.6);
    EXPECT_LT(world.car(0).speed(), 0.1) << "stopped";
}

}  // namespace
}  // namespace trackphys

namespace trackphys {
namespace {

// The mid phase only changes how triangles are found, never which contacts win: three
// seconds of driving in every mode end in the same state.
TEST(Autopilot, EveryMidPhaseModeDrivesTheSame) {
    const TrackWorld& tw = default_track();
    const CarSpec spec = CarSpec::default_car();
    std::vector<glm::dvec3> finals;
    for (const MidPhaseMode mode :
         {MidPhaseMode::none, MidPhaseMode::per_update_tree, MidPhaseMode::precomputed_tree}) {
        WorldSettings settings;
        settings.mid_phase = mode;
        World world(tw.statics, settings, tw.trees);
        world.add_car(spec, on_start_line(tw.track));
        Autopilot pilot(tw.track, spec);
        for (int i = 0; i < 300; ++i) {
            world.car(0).set_inputs(pilot.drive(world.car(0)));
            world.update();
        }
        finals.push_back(world.car(0).state().position);
    }
    EXPECT_LE(glm::length(finals[1] - finals[0]), 1e-9);
    EXPECT_LE(glm::length(finals[2] - finals[0]), 1e-9);
}

// Reusing a look-ahead query's list while the step's shape stays inside it changes which
// triangles are culled, never which contacts win: 1 (a query every step), the default and
// the whole update ahead end in the same state. The reuse must also happen.
TEST(Autopilot, LookingAheadInTheMidPhaseDrivesTheSame) {
    const TrackWorld& tw = default_track();
    const CarSpec spec = CarSpec::default_car();
    std::vector<glm::dvec3> finals;
    std::vector<std::uint64_t> queries;
    for (const int look_ahead : {1, WorldSettings{}.mid_phase_look_ahead, 10}) {
        WorldSettings settings;
        settings.mid_phase_look_ahead = look_ahead;
        World world(tw.statics, settings, tw.trees);
        world.add_car(spec, on_start_line(tw.track));
        Autopilot pilot(tw.track, spec);
        std::uint64_t listed = 0;
        for (int i = 0; i < 300; ++i) {
            world.car(0).set_inputs(pilot.drive(world.car(0)));
            world.update();
            listed += world.last_profile().mid_queries;
        }
        finals.push_back(world.car(0).state().position);
        queries.push_back(listed);
    }
    EXPECT_LE(glm::length(finals[1] - finals[0]), 1e-9);
    EXPECT_LE(glm::length(finals[2] - finals[0]), 1e-9);
    EXPECT_EQ(queries[0], 300u * 10u * spec.ellipsoids.size());
    EXPECT_LT(queries[1], queries[0] * 6 / 10);
    EXPECT_LT(queries[2], queries[1]);
}

}  // namespace
}  // namespace trackphys
