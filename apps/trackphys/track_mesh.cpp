#include "track_mesh.hpp"

namespace trackphys::cli {

// Chunk boundary rows stay duplicated: exporters keep them as they are.
TriangleMesh merge_chunks(const Track& track) {
    TriangleMesh merged;
    std::size_t vertex_count = 0;
    for (const TrackChunk& chunk : track.chunks) vertex_count += chunk.mesh.vertices.size();
    merged.vertices.reserve(vertex_count);
    merged.triangles.reserve(track.triangle_count());
    for (const TrackChunk& chunk : track.chunks) {
        const auto offset = static_cast<std::uint32_t>(merged.vertices.size());
        merged.vertices.insert(merged.vertices.end(), chunk.mesh.vertices.begin(),
                               chunk.mesh.vertices.end());
        for (const auto& t : chunk.mesh.triangles)
            merged.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
        merged.surfaces.insert(merged.surfaces.end(), chunk.mesh.surfaces.begin(),
                               chunk.mesh.surfaces.end());
        merged.surfaces.resize(merged.triangles.size());  // a chunk without ids: surface 0
    }
    return merged;
}

}  // namespace trackphys::cli
