#pragma once

#include "trackphys/geometry/triangle_mesh.hpp"
#include "trackphys/track/track.hpp"

namespace trackphys::cli {

/// All of the track's chunks as one mesh, in driving order (each chunk's indices offset by
/// the vertices before it), as `track --out` and `drive --record` write it.
TriangleMesh merge_chunks(const Track& track);

}  // namespace trackphys::cli
