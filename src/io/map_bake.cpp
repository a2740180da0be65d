// Baking: every collider and its plane tree, built on several threads.

#include <mutex>
#include <string>
#include <vector>

#include "core/parallel_items.hpp"
#include "trackphys/error.hpp"
#include "trackphys/io/map_file.hpp"

namespace trackphys {

StaticMap bake_map(std::span<const TriangleMesh> meshes, const PlaneTreeSettings& settings,
                   unsigned threads, const BakeProgress& progress) {
    const std::size_t n = meshes.size();
    std::vector<std::shared_ptr<const StaticCollider>> colliders(n);
    ColliderPlaneTrees trees(n);
    // Frames as a World's own trees or a loaded map's take them, so that a map driven where
    // it was baked (drive --mesh) queries as fast as the same map loaded. The meshes' count
    // is before degenerate triangles are dropped: near the budget it may choose built frames
    // where a load keeps them, which costs speed, never a different answer.
    std::size_t triangles = 0;
    for (const TriangleMesh& mesh : meshes) triangles += mesh.triangles.size();
    const PlaneTreeFrames frames = plane_tree_frames_within(triangles, kPlaneTreeFrameBudget);
    std::mutex progress_mutex;
    std::size_t built = 0;
    const unsigned threads_a_tree = detail::threads_per_item(n, threads);
    detail::run_items_in_parallel(n, threads, [&](std::size_t i) {
        try {
            auto collider = std::make_shared<StaticCollider>(meshes[i]);
            trees[i] = std::make_shared<PlaneTree>(
                make_collider_plane_tree(*collider, settings, frames, threads_a_tree));
            colliders[i] = std::move(collider);
        } catch (const Error& e) {
            if (n == 1) throw;
            throw Error("mesh " + std::to_string(i) + ": " + e.what());
        }
        if (progress) {
            const std::scoped_lock lock(progress_mutex);
            progress(++built, n);
        }
    });

    StaticMap map;
    map.plane_tree_settings = settings;
    auto world = std::make_shared<StaticWorld>();
    for (std::shared_ptr<const StaticCollider>& collider : colliders)
        world->add(std::move(collider));
    map.statics = std::move(world);
    map.plane_trees = std::move(trees);
    return map;
}

StaticMap bake_track_map(const Track& track, const PlaneTreeSettings& settings, unsigned threads,
                         const BakeProgress& progress) {
    std::vector<TriangleMesh> meshes;
    meshes.reserve(track.chunks.size());
    for (const TrackChunk& chunk : track.chunks) meshes.push_back(chunk.mesh);
    StaticMap map = bake_map(meshes, settings, threads, progress);
    map.track = Track{
        track.params,         track.length_m, track.centerline, {}, track.bezier_segment_count,
        track.rejected_shapes};
    return map;
}

}  // namespace trackphys
