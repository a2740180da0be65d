// Baking: every collider and its plane tree, built on several threads.

#include <algorithm>
#include <atomic>
#include <exception>
#include <thread>
#include <vector>

#include "trackphys/error.hpp"
#include "trackphys/io/map_file.hpp"

namespace trackphys {

StaticMap bake_map(std::span<const TriangleMesh> meshes, const PlaneTreeSettings& settings,
                   unsigned threads) {
    const std::size_t n = meshes.size();
    std::vector<std::shared_ptr<const StaticCollider>> colliders(n);
    ColliderPlaneTrees trees(n);
    std::vector<std::exception_ptr> errors(n);
    // Threads take the next mesh in turn; each result goes to its mesh's place, so the map
    // is the same whatever the thread count and the order they finish in.
    std::atomic<std::size_t> next{0};
    auto work = [&] {
        for (std::size_t i = next++; i < n; i = next++) {
            try {
                auto collider = std::make_shared<StaticCollider>(meshes[i]);
                trees[i] =
                    std::make_shared<PlaneTree>(make_collider_plane_tree(*collider, settings));
                colliders[i] = std::move(collider);
            } catch (...) {
                errors[i] = std::current_exception();
            }
        }
    };
    if (threads == 0) threads = std::max(1u, std::thread::hardware_concurrency());
    std::vector<std::jthread> pool;
    for (unsigned t = 1; t < std::min<std::size_t>(threads, n); ++t) pool.emplace_back(work);
    work();
    pool.clear();  // joins

    StaticMap map;
    map.plane_tree_settings = settings;
    auto world = std::make_shared<StaticWorld>();
    for (std::size_t i = 0; i < n; ++i) {
        if (errors[i]) {
            try {
                std::rethrow_exception(errors[i]);
            } catch (const Error& e) {
                throw Error("mesh " + std::to_string(i) + ": " + e.what());
            }
        }
        world->add(std::move(colliders[i]));
    }
    map.statics = std::move(world);
    map.plane_trees = std::move(trees);
    return map;
}

StaticMap bake_track_map(const Track& track, const PlaneTreeSettings& settings, unsigned threads) {
    std::vector<TriangleMesh> meshes;
    meshes.reserve(track.chunks.size());
    for (const TrackChunk& chunk : track.chunks) meshes.push_back(chunk.mesh);
    StaticMap map = bake_map(meshes, settings, threads);
    map.track = Track{
        track.params,         track.length_m, track.centerline, {}, track.bezier_segment_count,
        track.rejected_shapes};
    return map;
}

}  // namespace trackphys
