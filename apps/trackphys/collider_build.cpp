#include "collider_build.hpp"

#include <vector>

#include "counted_progress.hpp"
#include "interrupt_guard.hpp"
#include "mesh_reading.hpp"
#include "trackphys/error.hpp"
#include "trackphys/geometry/mesh_chunks.hpp"

namespace trackphys::cli {

StaticMap build_mesh_colliders(const std::filesystem::path& mesh, const MeshLoadLimits& limits,
                               double chunk_m, unsigned threads) {
    const std::vector<TriangleMesh> chunks = split_into_chunks(read_mesh(mesh, limits), chunk_m);
    InterruptGuard::check();
    CountedProgress progress("colliders");
    try {
        return bake_map(chunks, PlaneTreeSettings::precomputed(), threads, progress.callback());
    } catch (const Interrupted&) {
        throw;
    } catch (const Error& e) {  // a chunk the collider refuses (coordinates beyond its limit)
        throw Error("mesh file '" + mesh.string() + "': " + e.what());
    }
}

StaticMap build_track_colliders(const Track& track, unsigned threads) {
    CountedProgress progress("colliders");
    return bake_track_map(track, PlaneTreeSettings::precomputed(), threads, progress.callback());
}

}  // namespace trackphys::cli
