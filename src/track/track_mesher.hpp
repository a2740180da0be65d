#pragma once

#include <cstddef>
#include <vector>

#include <glm/vec3.hpp>

#include "trackphys/track/track.hpp"
#include "trackphys/track/track_params.hpp"

namespace trackphys::track_detail {

/// The cross-section of the track at one row, as one polyline from left to right:
///
///     0 left wall, outer bottom     1 left wall, outer top     2 left wall, inner top
///     3 .. 3 + strips               road, left edge to right edge (3 = left wall base)
///     then right wall inner top, outer top, outer bottom.
///
/// Joining the same polyline in two consecutive rows with quads (k, k+1) gives every
/// surface, and each quad's normal is (p[k+1] - p[k]) x tangent: going right across the
/// road (-left) that is up, going down the left wall's inner face (-Y) it is -left (it
/// looks at the road), up its outer face +left (away), and mirrored on the right. So one
/// winding rule makes road normals point up, walls face inward, tops up, backs outward.
/// Walls are vertical (world +Y) and their thickness is horizontal, whatever the bank.
std::vector<glm::dvec3> cross_section(const CenterlineSample& sample, const TrackParams& params);

/// Number of points in a cross-section: strips + 1 road points and 3 per wall.
inline std::size_t cross_section_size(const TrackParams& params) {
    return static_cast<std::size_t>(params.strips) + 7;
}

/// Index of the first road point of the cross-section (the left wall's base).
constexpr std::size_t kFirstRoadPoint = 3;

/// Splits the closed row sequence into chunks of about params.chunk_length_m and meshes
/// each. Row rows.size() (after the last) is row 0 again: the last chunk ends on row 0's
/// exact vertices, so the loop closes with zero error.
std::vector<TrackChunk> build_chunks(const std::vector<CenterlineSample>& rows, double length_m,
                                     const TrackParams& params);

}  // namespace trackphys::track_detail
