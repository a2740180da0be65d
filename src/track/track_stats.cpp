#include "trackphys/track/track_stats.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>

#include <glm/geometric.hpp>

namespace trackphys {
namespace {

// FNV-1a, 64 bit, fed one 64-bit word at a time (byte by byte, little end first).
struct Fnv1a {
    std::uint64_t state = 0xcbf29ce484222325ull;
    void add(std::uint64_t word) {
        for (int byte = 0; byte < 8; ++byte) {
            state ^= (word >> (8 * byte)) & 0xffu;
            state *= 0x100000001b3ull;
        }
    }
};

std::uint64_t hash_meshes(const Track& track) {
    Fnv1a hash;
    for (const TrackChunk& chunk : track.chunks) {
        for (const glm::dvec3& v : chunk.mesh.vertices)
            for (int axis = 0; axis < 3; ++axis) hash.add(std::bit_cast<std::uint64_t>(v[axis]));
        for (const auto& t : chunk.mesh.triangles)
            for (const std::uint32_t index : t) hash.add(index);
    }
    return hash.state;
}

}  // namespace

TrackStats compute_track_stats(const Track& track) {
    TrackStats stats;
    stats.length_m = track.length_m;
    stats.triangle_count = track.triangle_count();
    stats.road_triangle_count = track.road_triangle_count();
    stats.chunk_count = track.chunks.size();
    for (const TrackChunk& chunk : track.chunks) stats.vertex_count += chunk.mesh.vertices.size();

    constexpr double infinity = std::numeric_limits<double>::infinity();
    constexpr double to_degrees = 180.0 / std::numbers::pi;
    double min_bank = infinity, max_bank = -infinity;
    double min_y = infinity, max_y = -infinity;
    double max_curvature = 0.0;
    double min_edge = infinity, max_edge = 0.0;
    const std::size_t rows = track.centerline.size();
    for (std::size_t r = 0; r < rows; ++r) {
        const CenterlineSample& s = track.centerline[r];
        min_bank = std::min(min_bank, s.bank);
        max_bank = std::max(max_bank, s.bank);
        min_y = std::min(min_y, s.position.y);
        max_y = std::max(max_y, s.position.y);
        if (std::abs(s.curvature) > max_curvature) {
            max_curvature = std::abs(s.curvature);
            stats.tightest_sample = r;
        }
        // The outer road edge of the step to the next row: both edges, the longer one.
        const CenterlineSample& next = track.centerline[(r + 1) % rows];
        const double half = 0.5 * track.params.width_m;
        const double left =
            glm::distance(s.position + half * s.left, next.position + half * next.left);
        const double right =
            glm::distance(s.position - half * s.left, next.position - half * next.left);
        min_edge = std::min(min_edge, std::max(left, right));
        max_edge = std::max(max_edge, std::max(left, right));
    }
    stats.min_bank_deg = min_bank * to_degrees;
    stats.max_bank_deg = max_bank * to_degrees;
    stats.min_elevation_m = min_y;
    stats.max_elevation_m = max_y;
    stats.min_turn_radius_m = max_curvature > 0.0 ? 1.0 / max_curvature : infinity;
    stats.min_road_edge_m = min_edge;
    stats.max_road_edge_m = max_edge;
    stats.mesh_hash = hash_meshes(track);
    return stats;
}

Aabb car_update_box(const CenterlineSample& sample, const UpdateBoxSpec& spec) {
    // The car's centre sits half its height above the road, its box axes along left, up and
    // tangent; the world box of an oriented box has half-extent sum_i |axis_i| * half_i.
    const glm::dvec3 half = 0.5 * spec.car_size;
    const glm::dvec3 center = sample.position + half.y * sample.up;
    const glm::dvec3 extent = glm::abs(sample.left) * half.x + glm::abs(sample.up) * half.y +
                              glm::abs(sample.tangent) * half.z;
    // Swept along the road for one update: the box at the start, at the end and between.
    const glm::dvec3 travel = sample.tangent * (spec.speed_mps * spec.update_dt_s);
    Aabb swept{center - extent, center + extent};
    swept.expand(Aabb{center + travel - extent, center + travel + extent});
    return swept.padded(spec.margin_m);
}

BoxTriangleCount count_triangles_in_box(const Track& track, const Aabb& box) {
    BoxTriangleCount count;
    for (const TrackChunk& chunk : track.chunks) {
        if (!chunk.bounds.overlaps(box)) continue;
        const TriangleMesh& mesh = chunk.mesh;
        for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
            Aabb bounds;
            for (const std::uint32_t v : mesh.triangles[t]) bounds.expand(mesh.vertices[v]);
            if (!bounds.overlaps(box)) continue;
            if (t < chunk.road_triangle_count)
                ++count.road;
            else
                ++count.wall;
        }
    }
    return count;
}

}  // namespace trackphys
