#include "collider_build.hpp"

#include <vector>

#include "counted_progress.hpp"
#include "interrupt_guard.hpp"
#include "mesh_reading.hpp"
#include "trackphys/collision/static_collider.hpp"
#include "trackphys/error.hpp"
#include "trackphys/geometry/mesh_chunks.hpp"

namespace trackphys::cli {

StaticMap build_mesh_colliders(const std::filesystem::path& mesh, const MeshLoadLimits& limits,
                               double chunk_m, unsigned threads) {
    std::vector<TriangleMesh> chunks;
    {
        const TriangleMesh whole = read_mesh(mesh, limits);
        // Checked whole, as info checks it, so that a refusal names the mesh's vertex rather
        // than a cell's, and a mesh no collider takes (a vertex beyond 1e18 m) is never cut.
        try {
            StaticCollider::check(whole);
        } catch (const Error& e) {
            throw Error("mesh file '" + mesh.string() +
                        "': a static collider refuses it: " + e.what());
        }
        chunks = split_into_chunks(whole, chunk_m);
    }
    InterruptGuard::check();
    CountedProgress progress("colliders");
    return bake_map(chunks, PlaneTreeSettings::precomputed(), threads, progress.callback());
}

StaticMap build_track_colliders(const Track& track, unsigned threads) {
    CountedProgress progress("colliders");
    return bake_track_map(track, PlaneTreeSettings::precomputed(), threads, progress.callback());
}

}  // namespace trackphys::cli
