#include "tightest_turn_scene.hpp"

namespace trackphys::bench {

TriangleMesh merged_track_mesh(const Track& track) {
    TriangleMesh mesh;
    for (const TrackChunk& chunk : track.chunks) {
        const auto base = static_cast<std::uint32_t>(mesh.vertices.size());
        mesh.vertices.insert(mesh.vertices.end(), chunk.mesh.vertices.begin(),
                             chunk.mesh.vertices.end());
        for (const auto& t : chunk.mesh.triangles)
            mesh.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
    }
    return mesh;
}

TightestTurnScene::TightestTurnScene() {
    TrackParams params;
    params.seed = kDemoTrackSeed;
    track = generate_track(params);
    turn = track.centerline[compute_track_stats(track).tightest_sample];
    update_box = car_update_box(turn);
    ride_height = car.lowest_point_depth() - 0.01;
    // Body frame +X left, +Y up, +Z forward: the columns are the road frame there.
    car_orientation = glm::quat_cast(glm::dmat3(turn.left, turn.up, turn.tangent));
}

std::vector<BoundingSphere> TightestTurnScene::bounding_spheres() const {
    std::vector<BoundingSphere> spheres;
    for (int substep = 0; substep < kSubsteps; ++substep)
        for (std::size_t e = 0; e < car.ellipsoids.size(); ++e)
            spheres.push_back({center(e, substep), bounding_radius(e)});
    return spheres;
}

std::vector<Triangle> TightestTurnScene::candidates() const {
    std::vector<Triangle> out;
    for (const TrackChunk& chunk : track.chunks) {
        if (!chunk.bounds.overlaps(update_box)) continue;
        for (const auto& t : chunk.mesh.triangles) {
            const Triangle triangle(chunk.mesh.vertices[t[0]], chunk.mesh.vertices[t[1]],
                                    chunk.mesh.vertices[t[2]]);
            if (triangle.bounds().overlaps(update_box)) out.push_back(triangle);
        }
    }
    return out;
}

const TightestTurnScene& tightest_turn_scene() {
    static const TightestTurnScene instance;  // generating the track takes ~0.1 s
    return instance;
}

}  // namespace trackphys::bench
