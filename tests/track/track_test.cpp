#include "trackphys/track/track.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "trackphys/geometry/triangle.hpp"
#include "trackphys/track/track_stats.hpp"

namespace trackphys {
namespace {

constexpr double kDegrees = std::numbers::pi / 180.0;

// The default track, generated once for the whole suite (~20 ms).
const Track& default_track() {
    static const Track track = generate_track(TrackParams{});
    return track;
}

Triangle triangle_of(const TriangleMesh& mesh, std::size_t t) {
    const auto& ids = mesh.triangles[t];
    return Triangle(mesh.vertices[ids[0]], mesh.vertices[ids[1]], mesh.vertices[ids[2]]);
}

// Vertices per row of a chunk mesh (rows are stored one after the other).
std::size_t row_size(const Track& track) {
    const std::size_t rows = track.chunks[0].mesh.vertices.size();
    const std::size_t steps =
        track.chunks.size() > 1 ? track.chunks[1].first_sample : track.centerline.size();
    return rows / (steps + 1);
}

TEST(Track, DefaultHasTheRequestedSize) {
    const Track& track = default_track();
    EXPECT_NEAR(track.length_m, 5000.0, 5000.0 * 1e-6);
    EXPECT_EQ(track.chunks.size(), 50u);
    // The budget of the README: a few hundred thousand triangles, road plus walls.
    EXPECT_GT(track.triangle_count(), 150'000u);
    EXPECT_LT(track.triangle_count(), 1'000'000u);
    EXPECT_GT(track.road_triangle_count(), track.triangle_count() / 3);
}

TEST(Track, LoopClosesExactly) {
    const Track& track = default_track();
    const std::size_t width = row_size(track);
    const TriangleMesh& first = track.chunks.front().mesh;
    const TriangleMesh& last = track.chunks.back().mesh;
    ASSERT_GT(last.vertices.size(), width);
    for (std::size_t k = 0; k < width; ++k) {
        const glm::dvec3& end = last.vertices[last.vertices.size() - width + k];
        EXPECT_LE(glm::distance(end, first.vertices[k]), 1e-9) << "point " << k;
    }
    // Neighbouring chunks share their boundary row exactly.
    for (std::size_t c = 0; c + 1 < track.chunks.size(); ++c) {
        const TriangleMesh& a = track.chunks[c].mesh;
        const TriangleMesh& b = track.chunks[c + 1].mesh;
        for (std::size_t k = 0; k < width; ++k)
            ASSERT_EQ(a.vertices[a.vertices.size() - width + k], b.vertices[k]) << "chunk " << c;
    }
    // The centreline is continuous across the closing point: the last step is an ordinary one.
    const CenterlineSample& end = track.centerline.back();
    const CenterlineSample& start = track.centerline.front();
    EXPECT_EQ(start.distance, 0.0);
    EXPECT_LT(end.distance, track.length_m);
    EXPECT_NEAR(glm::distance(end.position, start.position), track.length_m - end.distance, 1e-3);
}

TEST(Track, CenterlineFramesAreOrthonormalAndDistancesIncrease) {
    const Track& track = default_track();
    for (std::size_t r = 0; r < track.centerline.size(); ++r) {
        const CenterlineSample& s = track.centerline[r];
        ASSERT_NEAR(glm::length(s.tangent), 1.0, 1e-12);
        ASSERT_NEAR(glm::length(s.up), 1.0, 1e-12);
        ASSERT_LE(glm::distance(s.left, glm::cross(s.up, s.tangent)), 1e-12);
        ASSERT_NEAR(glm::dot(s.up, s.tangent), 0.0, 1e-12);
        if (r > 0) {
            const CenterlineSample& previous = track.centerline[r - 1];
            ASSERT_GT(s.distance, previous.distance);
            // Distance is arc length: it exceeds the chord by kappa^2 d^3 / 24 (kappa the 3-D
            // curvature, below 1/20 m here), and is never shorter.
            const double arc = s.distance - previous.distance;
            const double chord = glm::distance(s.position, previous.position);
            ASSERT_GE(arc, chord - 1e-9);
            ASSERT_LE(arc - chord, arc * arc * arc / (24.0 * 20.0 * 20.0) + 1e-12);
        }
    }
}

TEST(Track, WidthAndBankStayWithinBounds) {
    const Track& track = default_track();
    const double max_bank = track.params.max_bank_deg * kDegrees;
    double largest = 0.0;
    for (const CenterlineSample& s : track.centerline) {
        ASSERT_LE(std::abs(s.bank), max_bank + 1e-12);
        largest = std::max(largest, std::abs(s.bank));
        // The road is banked the right way: the inside of a turn is the low side.
        if (std::abs(s.curvature) > 1.0 / 100.0) {
            ASSERT_GT(s.bank * s.curvature, 0.0);
        }
    }
    // The tight turns of this track reach the full bank, but for the 120 m over which the
    // bank swings between turns (road_profile.cpp), which rounds off the shortest plateaus.
    EXPECT_GT(largest, 0.98 * max_bank);

    // Each row's road spans exactly the width between its edge vertices, and the bank of
    // the road surface is the sample's bank.
    const std::size_t width = row_size(track);
    for (const TrackChunk& chunk : track.chunks) {
        for (std::size_t row = 0; row * width < chunk.mesh.vertices.size(); ++row) {
            const glm::dvec3& left = chunk.mesh.vertices[row * width + 3];
            const glm::dvec3& right = chunk.mesh.vertices[row * width + 3 + track.params.strips];
            ASSERT_NEAR(glm::distance(left, right), track.params.width_m, 1e-9);
            const double drop =
                (right.y - left.y) / track.params.width_m;  // sin(bank) for a level road
            const CenterlineSample& s =
                track.centerline[(chunk.first_sample + row) % track.centerline.size()];
            ASSERT_NEAR(drop, std::sin(s.bank) * std::sqrt(1.0 - s.tangent.y * s.tangent.y), 1e-9);
        }
    }
}

TEST(Track, RoadTrianglesAreSoundAndFaceUp) {
    const Track& track = default_track();
    // A road normal tilts from +Y by the bank and the grade (a few degrees) at most.
    const double min_up = std::cos(track.params.max_bank_deg * kDegrees + 10.0 * kDegrees);
    std::size_t checked = 0;
    for (const TrackChunk& chunk : track.chunks) {
        for (std::size_t t = 0; t < chunk.road_triangle_count; ++t) {
            const Triangle tri = triangle_of(chunk.mesh, t);
            ASSERT_FALSE(tri.is_degenerate(0.05)) << "road triangle " << t;
            ASSERT_GT(tri.area(), 0.05);
            ASSERT_GT(tri.normal().y, min_up)
                << "road triangle " << t << " is flipped or too steep";
            ++checked;
        }
    }
    EXPECT_EQ(checked, track.road_triangle_count());
}

TEST(Track, WallsStandAtBothEdgesAndFaceTheRoad) {
    const Track& track = default_track();
    const TrackParams& p = track.params;
    std::size_t inner = 0, outer = 0, top = 0;
    const std::size_t width = row_size(track);
    for (const TrackChunk& chunk : track.chunks) {
        const TriangleMesh& mesh = chunk.mesh;
        for (std::size_t t = chunk.road_triangle_count; t < mesh.triangles.size(); ++t) {
            const Triangle tri = triangle_of(mesh, t);
            ASSERT_FALSE(tri.is_degenerate(0.05)) << "wall triangle " << t;
            const glm::dvec3 n = tri.normal();
            // Tops tilt with the grade and the bank's twist; faces are exactly vertical
            // (every face triangle has a vertical edge).
            if (n.y > 0.8) {
                ++top;
                continue;
            }
            ASSERT_LT(std::abs(n.y), 1e-9) << "wall faces are vertical";
            // The centreline point of the row this triangle starts on.
            const std::size_t row = mesh.triangles[t][0] / width;
            const CenterlineSample& s =
                track.centerline[(chunk.first_sample + row) % track.centerline.size()];
            const glm::dvec3 centroid = (tri[0] + tri[1] + tri[2]) / 3.0;
            glm::dvec3 towards = s.position - centroid;
            towards.y = 0.0;
            const double distance = glm::length(towards);
            // Inner faces stand at the road edge (w/2 cos(bank) across) and look at the
            // road; outer faces a wall thickness further out, looking away.
            const double facing = glm::dot(n, towards / distance);
            if (facing > 0.95) {
                ++inner;
                ASSERT_LT(distance, 0.5 * p.width_m + 0.5 * p.wall_thickness_m);
            } else {
                ASSERT_LT(facing, -0.95);
                ++outer;
                ASSERT_GT(distance, 0.5 * p.width_m * std::cos(p.max_bank_deg * kDegrees));
            }
            const double height =
                std::max({tri[0].y, tri[1].y, tri[2].y}) - std::min({tri[0].y, tri[1].y, tri[2].y});
            ASSERT_GT(height, 0.99 * p.wall_height_m);
        }
    }
    // Two walls, each an inner face, a top and an outer face of 2 triangles per row step.
    const std::size_t steps = track.centerline.size();
    EXPECT_EQ(inner, 4 * steps);
    EXPECT_EQ(outer, 4 * steps);
    EXPECT_EQ(top, 4 * steps);
}

TEST(Track, ChunkBoundsHoldTheirTriangles) {
    const Track& track = default_track();
    for (const TrackChunk& chunk : track.chunks) {
        Aabb tight;
        for (const auto& ids : chunk.mesh.triangles)
            for (const std::uint32_t v : ids) {
                ASSERT_LT(v, chunk.mesh.vertices.size());
                ASSERT_TRUE(chunk.bounds.contains(chunk.mesh.vertices[v]));
                tight.expand(chunk.mesh.vertices[v]);
            }
        EXPECT_EQ(tight.min, chunk.bounds.min);
        EXPECT_EQ(tight.max, chunk.bounds.max);
    }
    // Chunks are about chunk_length_m of centreline each.
    for (std::size_t c = 0; c < track.chunks.size(); ++c) {
        const double from = track.centerline[track.chunks[c].first_sample].distance;
        const double to = c + 1 < track.chunks.size()
                              ? track.centerline[track.chunks[c + 1].first_sample].distance
                              : track.length_m;
        EXPECT_NEAR(to - from, track.params.chunk_length_m, 1.0) << "chunk " << c;
    }
}

TEST(Track, SameSeedSameTrackOtherSeedOtherTrack) {
    TrackParams params;
    params.seed = 7;
    params.length_m = 2000.0;
    const Track a = generate_track(params);
    const Track b = generate_track(params);
    ASSERT_EQ(a.chunks.size(), b.chunks.size());
    for (std::size_t c = 0; c < a.chunks.size(); ++c) {
        ASSERT_EQ(a.chunks[c].mesh.vertices, b.chunks[c].mesh.vertices);
        ASSERT_EQ(a.chunks[c].mesh.triangles, b.chunks[c].mesh.triangles);
    }
    EXPECT_EQ(compute_track_stats(a).mesh_hash, compute_track_stats(b).mesh_hash);
    params.seed = 8;
    const Track other = generate_track(params);
    EXPECT_NE(compute_track_stats(other).mesh_hash, compute_track_stats(a).mesh_hash);
    const bool same_rows = other.centerline.size() == a.centerline.size();
    EXPECT_FALSE(same_rows && other.chunks[0].mesh.vertices == a.chunks[0].mesh.vertices);
    EXPECT_GT(glm::distance(other.centerline[100].position, a.centerline[100].position), 1.0);
}

TEST(Track, RowsAreDenserInTightTurns) {
    // Coarse straights make the contrast plain: 0.5 m in tight turns, 3 m on straights.
    TrackParams params;
    params.seed = 4;
    params.edge_straight_m = 3.0;
    const Track track = generate_track(params);
    const double half = 0.5 * params.width_m;
    double tight_sum = 0.0, open_sum = 0.0, tight_max = 0.0;
    std::size_t tight_count = 0, open_count = 0;
    const std::size_t rows = track.centerline.size();
    for (std::size_t r = 0; r < rows; ++r) {
        const CenterlineSample& s = track.centerline[r];
        const CenterlineSample& next = track.centerline[(r + 1) % rows];
        // The outer road edge of this row step (the longer of the two edges).
        const double edge =
            std::max(glm::distance(s.position + half * s.left, next.position + half * next.left),
                     glm::distance(s.position - half * s.left, next.position - half * next.left));
        const double radius = 1.0 / std::max(std::abs(s.curvature), 1e-12);
        if (radius <= params.tight_radius_m) {
            tight_sum += edge;
            tight_max = std::max(tight_max, edge);
            ++tight_count;
        } else if (radius > 2000.0) {
            open_sum += edge;
            ++open_count;
        }
    }
    ASSERT_GT(tight_count, 50u) << "seed 4 has tight turns";
    ASSERT_GT(open_count, 50u) << "seed 4 has straights";
    EXPECT_LE(tight_max, 1.05 * params.edge_tight_m);
    const double tight_mean = tight_sum / static_cast<double>(tight_count);
    const double open_mean = open_sum / static_cast<double>(open_count);
    EXPECT_LT(tight_mean, 0.3 * open_mean);
    EXPECT_GT(open_mean, 0.8 * params.edge_straight_m);
}

TEST(Track, ElevationFollowsTheAmplitude) {
    TrackParams params;
    params.length_m = 2000.0;
    params.elevation_amplitude_m = 0.0;
    const Track flat = generate_track(params);
    for (const CenterlineSample& s : flat.centerline) ASSERT_EQ(s.position.y, 0.0);

    // 12 control points ~167 m apart: the amplitude is capped at 4% of that, 6.7 m.
    params.elevation_amplitude_m = 50.0;
    const Track hilly = generate_track(params);
    const TrackStats stats = compute_track_stats(hilly);
    EXPECT_GT(stats.max_elevation_m - stats.min_elevation_m, 5.0);
    // Catmull-Rom overshoots its control points only a little.
    EXPECT_LT(stats.max_elevation_m, 1.3 * 2000.0 / 12 * 0.04);
    EXPECT_GT(stats.min_elevation_m, -1.3 * 2000.0 / 12 * 0.04);
    double max_grade = 0.0;
    for (const CenterlineSample& s : hilly.centerline)
        max_grade =
            std::max(max_grade, std::abs(s.tangent.y) / std::hypot(s.tangent.x, s.tangent.z));
    EXPECT_LT(max_grade, 0.15);
}

TEST(Track, NeverComesCloseToItself) {
    // Brute force, independent of the generator's own grid check: centreline points far
    // apart along the track are at least two roads with walls apart, seen from above.
    const Track& track = default_track();
    const TrackParams& p = track.params;
    const double clearance = p.width_m + 2.0 * p.wall_thickness_m;
    std::vector<const CenterlineSample*> points;
    for (std::size_t r = 0; r < track.centerline.size(); r += 4)
        points.push_back(&track.centerline[r]);
    for (std::size_t i = 0; i < points.size(); ++i) {
        for (std::size_t j = i + 1; j < points.size(); ++j) {
            const double along = points[j]->distance - points[i]->distance;
            if (std::min(along, track.length_m - along) < std::numbers::pi * p.min_turn_radius_m)
                continue;
            const glm::dvec3 d = points[j]->position - points[i]->position;
            ASSERT_GE(std::hypot(d.x, d.z), clearance)
                << "at " << points[i]->distance << " m and " << points[j]->distance << " m";
        }
    }
}

TEST(Track, OtherParametersMakeValidTracksToo) {
    TrackParams params;
    params.seed = 99;
    params.length_m = 1200.0;
    params.width_m = 9.0;
    params.strips = 3;
    params.max_bank_deg = 10.0;
    params.chunk_length_m = 37.0;
    const Track track = generate_track(params);
    EXPECT_NEAR(track.length_m, 1200.0, 1e-3);
    EXPECT_EQ(track.chunks.size(), 32u);
    for (const CenterlineSample& s : track.centerline)
        ASSERT_LE(std::abs(s.bank), 10.0 * kDegrees + 1e-12);
    for (const TrackChunk& chunk : track.chunks)
        for (std::size_t t = 0; t < chunk.road_triangle_count; ++t)
            ASSERT_GT(triangle_of(chunk.mesh, t).normal().y, 0.9);
}

TEST(TrackStats, UpdateBoxInTheTightestTurnHoldsAFewHundredTriangles) {
    const Track& track = default_track();
    const TrackStats stats = compute_track_stats(track);
    EXPECT_EQ(stats.triangle_count, track.triangle_count());
    EXPECT_LT(stats.min_turn_radius_m, 60.0);
    EXPECT_GE(stats.min_turn_radius_m, track.params.min_turn_radius_m * 0.99);
    const CenterlineSample& tightest = track.centerline[stats.tightest_sample];
    const Aabb box = car_update_box(tightest);
    EXPECT_TRUE(box.contains(tightest.position));
    const BoxTriangleCount count = count_triangles_in_box(track, box);
    // The figure the broad phase is sized for: a couple of hundred road triangles.
    EXPECT_GT(count.road, 150u);
    EXPECT_LT(count.road, 500u);
}

TEST(TrackStats, CarUpdateBoxIsTheOrientedCarSweptByOneUpdateOfTravel) {
    CenterlineSample s;
    s.position = {10.0, 2.0, -3.0};
    s.tangent = {0.0, 0.0, 1.0};
    s.up = {0.0, 1.0, 0.0};
    s.left = {1.0, 0.0, 0.0};
    UpdateBoxSpec spec;
    spec.car_size = {2.0, 1.2, 4.5};
    spec.speed_mps = 100.0;
    spec.update_dt_s = 0.01;
    spec.margin_m = 0.5;
    const Aabb box = car_update_box(s, spec);
    // Half extents 1, 0.6, 2.25 about a centre 0.6 m above the road, swept 1 m along +z,
    // plus 0.5 m on every side.
    EXPECT_NEAR(box.min.x, 10.0 - 1.5, 1e-12);
    EXPECT_NEAR(box.max.x, 10.0 + 1.5, 1e-12);
    EXPECT_NEAR(box.max.y, 2.0 + 1.2 + 0.5, 1e-12);
    EXPECT_NEAR(box.min.y, 2.0 - 0.5, 1e-12);
    EXPECT_NEAR(box.min.z, -3.0 - 2.25 - 0.5, 1e-12);
    EXPECT_NEAR(box.max.z, -3.0 + 2.25 + 1.0 + 0.5, 1e-12);
}

}  // namespace
}  // namespace trackphys
