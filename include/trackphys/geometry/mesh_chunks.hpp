#pragma once

#include <vector>

#include "trackphys/export.hpp"
#include "trackphys/geometry/triangle_mesh.hpp"

namespace trackphys {

/// Splits a mesh into chunks for one collider each, as the generated track comes in ~100 m
/// chunks: square cells of `cell_m` (m, finite, > 0) on the ground plane (x, z; +Y is up),
/// each triangle in the cell of its centroid. Each chunk keeps only the vertices its
/// triangles use, in order of first use, and its triangles in mesh order; chunks come in
/// order of their cells (by x, then z), empty cells left out, each triangle with its surface
/// id when the mesh has them. Coordinates are copied exactly, so the union of the chunks is
/// the mesh. Throws trackphys::Error on a bad cell size, a triangle index out of range or
/// surface ids that are neither none nor one per triangle.
TRACKPHYS_API std::vector<TriangleMesh> split_into_chunks(const TriangleMesh& mesh, double cell_m);

}  // namespace trackphys
