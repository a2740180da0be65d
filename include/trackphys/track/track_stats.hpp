#pragma once

#include <cstddef>
#include <cstdint>

#include <glm/vec3.hpp>

#include "trackphys/export.hpp"
#include "trackphys/geometry/aabb.hpp"
#include "trackphys/math/types.hpp"
#include "trackphys/track/track.hpp"

namespace trackphys {

/// Summary figures of a generated track (what `trackphys track` prints).
struct TrackStats {
    double length_m = 0.0;           ///< centreline length (m)
    std::size_t triangle_count = 0;  ///< all triangles, road and walls
    std::size_t road_triangle_count = 0;
    std::size_t vertex_count = 0;  ///< over all chunks (boundary rows counted twice)
    std::size_t chunk_count = 0;   ///< collider count
    double min_bank_deg = 0.0;     ///< most negative bank (right-hand turns), degrees
    double max_bank_deg = 0.0;
    double min_elevation_m = 0.0;  ///< lowest centreline point (y, m)
    double max_elevation_m = 0.0;
    double min_turn_radius_m = 0.0;   ///< tightest centreline radius seen from above (m)
    std::size_t tightest_sample = 0;  ///< centreline sample with the largest |curvature|
    double min_road_edge_m = 0.0;     ///< shortest along-track road edge (outer edge, m)
    double max_road_edge_m = 0.0;     ///< longest along-track road edge (outer edge, m)
    /// FNV-1a hash of every chunk's vertex bits and indices: equal hashes mean the same
    /// meshes, bit for bit (a quick check that a seed reproduces its track).
    std::uint64_t mesh_hash = 0;
};

/// Computes the summary of track (linear in its size).
TRACKPHYS_API TrackStats compute_track_stats(const Track& track);

/// A car's broad-phase box for one physics update: the car's oriented box sitting on the
/// road at a centreline sample, as an axis-aligned world box, swept along the road by the
/// distance it travels in one update (the box at the start, at the end and everything
/// between), plus a margin on every side: the box the world's broad phase queries.
struct UpdateBoxSpec {
    /// Car box size (m): x = width (along left), y = height (along up), z = length (along
    /// the tangent).
    glm::dvec3 car_size{2.0, 1.2, 4.5};
    double speed_mps = 1000.0 / 3.6;  ///< top speed (m/s): 1000 km/h
    double update_dt_s = 0.01;        ///< one physics update (s)
    double margin_m = 0.1;            ///< extra padding (m)
};

/// The padded world box of a car standing on the road at sample (see UpdateBoxSpec).
TRACKPHYS_API Aabb car_update_box(const CenterlineSample& sample, const UpdateBoxSpec& spec = {});

/// Triangles of track whose bounding box overlaps box (brute force over every chunk).
struct BoxTriangleCount {
    std::size_t road = 0;
    std::size_t wall = 0;
};

/// Counts, by brute force, the road and wall triangles whose AABB overlaps box: the
/// broad-phase candidates a car gets in that box.
TRACKPHYS_API BoxTriangleCount count_triangles_in_box(const Track& track, const Aabb& box);

}  // namespace trackphys
