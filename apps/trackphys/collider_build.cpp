#include "collider_build.hpp"

#include <optional>
#include <vector>

#include "interrupt_guard.hpp"
#include "progress_bar.hpp"
#include "trackphys/error.hpp"
#include "trackphys/geometry/mesh_chunks.hpp"
#include "trackphys/io/mesh_io.hpp"

namespace trackphys::cli {
namespace {

// A map of millions of triangles builds for tens of seconds: a bar of its colliders (made at
// the first call, which knows the total; its line closed when the bar goes), which also
// lets Ctrl-C in: bake_map stops at a progress call that throws.
class ColliderBar {
  public:
    BakeProgress progress() {
        return [this](std::size_t done, std::size_t total) {
            InterruptGuard::check();
            if (!bar_) bar_.emplace(static_cast<double>(total));
            bar_->show_count(static_cast<double>(done), "colliders");
        };
    }

  private:
    std::optional<ProgressBar> bar_;
};

}  // namespace

StaticMap build_mesh_colliders(const std::filesystem::path& mesh, const MeshLoadLimits& limits,
                               double chunk_m, unsigned threads) {
    const std::vector<TriangleMesh> chunks = split_into_chunks(load_mesh(mesh, limits), chunk_m);
    InterruptGuard::check();
    ColliderBar bar;
    try {
        return bake_map(chunks, PlaneTreeSettings::precomputed(), threads, bar.progress());
    } catch (const Interrupted&) {
        throw;
    } catch (const Error& e) {  // a chunk the collider refuses (coordinates beyond its limit)
        throw Error("mesh file '" + mesh.string() + "': " + e.what());
    }
}

StaticMap build_track_colliders(const Track& track, unsigned threads) {
    ColliderBar bar;
    return bake_track_map(track, PlaneTreeSettings::precomputed(), threads, bar.progress());
}

}  // namespace trackphys::cli
