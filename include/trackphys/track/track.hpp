#pragma once

#include <cstddef>
#include <vector>

#include <glm/vec3.hpp>

#include "trackphys/export.hpp"
#include "trackphys/geometry/aabb.hpp"
#include "trackphys/geometry/triangle_mesh.hpp"
#include "trackphys/math/types.hpp"
#include "trackphys/track/track_params.hpp"

namespace trackphys {

/// One point of the centreline with the road frame there. tangent, left and up are unit and
/// mutually orthogonal with left = up x tangent (so +X left, +Y up, +Z forward matches the
/// car body frame when a car sits on the sample facing forward).
struct CenterlineSample {
    glm::dvec3 position{0.0};  ///< centre of the road surface (m)
    glm::dvec3 tangent{0.0};   ///< direction of travel (follows grades)
    glm::dvec3 up{0.0};        ///< road surface normal, tilted by the bank
    glm::dvec3 left{0.0};      ///< across the road, towards the left edge (banked)
    /// Signed curvature of the centreline seen from above (1/m), > 0 when turning left.
    double curvature = 0.0;
    /// Bank angle (rad), > 0 when the left side is lower (a banked left turn).
    double bank = 0.0;
    /// Arc length from the start line along the centreline (m), in [0, Track::length_m).
    double distance = 0.0;
};

/// The surface ids the track generator gives its triangles (TriangleMesh::surfaces): a game
/// tunes them in WorldSettings::surfaces (two entries, or none for grip 1 everywhere).
inline constexpr SurfaceId kRoadSurface = 0;
inline constexpr SurfaceId kWallSurface = 1;

/// One static collider: a piece of the track about chunk_length_m long. Its first
/// road_triangle_count triangles are road surface (normals up, kRoadSurface), the rest are
/// wall faces (inner faces look at the road, tops up, outer faces away; kWallSurface).
/// Neighbouring chunks share their boundary row of vertices exactly (equal coordinates,
/// duplicated).
struct TrackChunk {
    TriangleMesh mesh;                    ///< world-space vertices (m), CCW triangles
    Aabb bounds;                          ///< tight box of mesh.vertices
    std::size_t road_triangle_count = 0;  ///< triangles [0, this) are road
    std::size_t first_sample = 0;         ///< centreline sample of the chunk's first row
};

/// A generated closed track: collider chunks in driving order and the centreline.
struct Track {
    TrackParams params;     ///< the (validated) parameters it came from
    double length_m = 0.0;  ///< centreline length (m), 3-D arc length
    /// One sample per row of mesh vertices, in driving order; row spacing adapts to the
    /// curvature (denser in tight turns). The loop closes: the row after the last sample
    /// is sample 0 again (its vertices are exactly sample 0's).
    std::vector<CenterlineSample> centerline;
    /// Collider chunks in driving order; chunk c starts at centreline sample
    /// chunks[c].first_sample and ends on the first row of chunk c + 1 (of chunk 0 for the last).
    std::vector<TrackChunk> chunks;
    /// Number of Bezier segments (control points) of the centreline.
    std::size_t bezier_segment_count = 0;
    /// How many control-point sets were rejected (self-intersection, too-tight turn)
    /// before this one was accepted; each retry relaxes the shape towards a circle.
    int rejected_shapes = 0;

    /// Total triangles over all chunks.
    TRACKPHYS_API std::size_t triangle_count() const;
    /// Road triangles over all chunks.
    TRACKPHYS_API std::size_t road_triangle_count() const;
};

/// Generates the track: a closed loop of C1 cubic Bezier segments through seeded random
/// control points, scaled to params.length_m, checked for self-intersection and turns
/// tighter than params.min_turn_radius_m (a failing shape is redrawn, deterministically,
/// each time closer to a circle), then banked, walled and tessellated into chunks.
/// Throws trackphys::Error on invalid params (see validate_track_params) or when no valid
/// shape is found.
TRACKPHYS_API Track generate_track(const TrackParams& params);

}  // namespace trackphys
