#pragma once

#include <cstddef>
#include <functional>
#include <optional>

#include "progress_bar.hpp"

namespace trackphys::cli {

/// Progress of long work counted in items whose total its first report tells (a mesh file's
/// triangles, a map's colliders): a bar of them on a terminal ("1234 of 3000 colliders"),
/// made at the first report and closed with this object, and a stop at every report once
/// Ctrl-C came under the command's InterruptGuard (InterruptGuard::check throws Interrupted,
/// which load_mesh and bake_map let out as it is).
class CountedProgress {
  public:
    /// unit: what is counted, plural ("colliders").
    explicit CountedProgress(const char* unit) : unit_(unit) {}

    /// The callback for load_mesh (MeshLoadProgress) or bake_map (BakeProgress); it reports
    /// to this object, which must outlive it.
    std::function<void(std::size_t done, std::size_t total)> callback();

  private:
    const char* unit_;
    std::optional<ProgressBar> bar_;
};

}  // namespace trackphys::cli
