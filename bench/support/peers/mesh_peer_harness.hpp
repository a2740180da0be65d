#pragma once

// Mesh box queries (the harness): Bullet's btBvhTriangleMeshShape (quantized BVH over a
// btTriangleIndexVertexArray of the same mesh) against our StaticCollider, with the same
// padded car boxes, on two ~300k-triangle meshes: the default generated track (seed 7, all
// chunks as one mesh) and the 300k-triangle BankedLoop at scale 2 (bench_collision_bvh's).
//
// Per mesh: build time (one build each, ms), bytes per triangle (ours: bytes_used(), every
// structure; Bullet: its node arrays - quantized contiguous nodes, subtree headers, leaf
// nodes, by capacity - and with the int index and btScalar vertex arrays it reads the mesh
// from), and the median time per query over the boxes (us, each query timed alone) for:
// - ours: StaticCollider::query_aabb (indices of the triangles whose box overlaps);
// - bullet_nodes: btQuantizedBvh::reportAabbOverlappingNodex with a callback collecting
//   the triangle indices (Bullet's cheapest box query);
// - bullet_exact: btBvhTriangleMeshShape::processAllTriangles, which also fetches each
//   reported triangle's vertices (what Bullet's concave collision does), with a callback
//   that keeps the triangles whose box overlaps the query: the exact set ours returns.
// Each mesh gets two sets of boxes (10k each, 500 with --quick): "random" places on the
// road (cold caches) and "drive", one car at 1000 km/h, a box per 10 ms update (warm).
// Table columns: x_node = bt_node / us and x_exact = bt_exact / us (> 1: ours faster).
// Triangle sets: Bullet tests quantized boxes (16-bit, rounded outward, and leaf boxes at
// least 2 mm thick), so it may report a superset. The check: ours is a subset of Bullet's
// on every box, every extra lies within the quantisation slack of the box, and no extra
// overlaps the box where ours kept the triangle ("miss" counts both failures). Exit code 1
// otherwise.
//
//   (header-only: bench_peers_mesh_bullet_* and trackphys-bench run the same queries)

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <random>
#include <string>
#include <string_view>
#include <vector>

#include <BulletCollision/CollisionShapes/btBvhTriangleMeshShape.h>
#include <BulletCollision/CollisionShapes/btTriangleCallback.h>
#include <BulletCollision/CollisionShapes/btTriangleIndexVertexArray.h>

#include "collision/collision_meshes.hpp"
#include "peers/bullet_contact.hpp"
#include "tightest_turn_scene.hpp"
#include "trackphys/collision/static_collider.hpp"
#include "trackphys/track/track.hpp"

namespace trackphys::peers {

using Clock = std::chrono::steady_clock;

// bench_collision_bvh's car box: 1000 km/h for one 10 ms update, and the padding.
constexpr double kTravel = 2.8;
constexpr double kMargin = 0.25;

/// A car's swept, padded box on a road frame, as BankedLoop::car_box: a 4.5 x 1.2 x 2 m box
/// resting on the road, moved kTravel along the tangent, padded by kMargin.
inline Aabb car_box(const glm::dvec3& center, const glm::dvec3& tangent, const glm::dvec3& left,
                    const glm::dvec3& up) {
    const glm::dvec3 half = glm::abs(tangent) * 2.25 + glm::abs(up) * 0.6 + glm::abs(left) * 1.0;
    const glm::dvec3 c = center + up * 0.6;
    Aabb box{c - half, c + half};
    box.expand(Aabb{box.min + tangent * kTravel, box.max + tangent * kTravel});
    return box.padded(kMargin);
}

/// A mesh and two sets of car boxes: "random" (anywhere on the road: cold caches) and
/// "drive" (one car at 1000 km/h, a box per 10 ms update, kTravel apart: warm caches).
struct Scene {
    std::string name;
    TriangleMesh mesh;
    std::vector<Aabb> random_boxes, drive_boxes;
};

/// The default track (seed 7) as one mesh. Random boxes: at random centreline samples
/// (denser in turns, so turns get more boxes), a random place across the road. Drive: on the
/// centreline, the sample at or before each kTravel step of arc length.
inline Scene track_scene(std::size_t box_count) {
    TrackParams params;
    params.seed = kDemoTrackSeed;
    const Track track = generate_track(params);
    Scene scene{"default_track_seed7", bench::merged_track_mesh(track), {}, {}};
    std::mt19937_64 rng(5);
    std::uniform_int_distribution<std::size_t> sample(0, track.centerline.size() - 1);
    const double half_road = 0.5 * track.params.width_m - 1.0;
    std::uniform_real_distribution<double> across(-half_road, half_road);
    for (std::size_t i = 0; i < box_count; ++i) {
        const CenterlineSample& s = track.centerline[sample(rng)];
        scene.random_boxes.push_back(
            car_box(s.position + s.left * across(rng), s.tangent, s.left, s.up));
    }
    std::size_t at = 0;
    for (std::size_t k = 0; k < box_count; ++k) {
        const double distance = std::fmod(double(k) * kTravel, track.length_m);
        if (distance < track.centerline[at].distance) at = 0;  // a new lap
        while (at + 1 < track.centerline.size() && track.centerline[at + 1].distance <= distance)
            ++at;
        const CenterlineSample& s = track.centerline[at];
        scene.drive_boxes.push_back(car_box(s.position, s.tangent, s.left, s.up));
    }
    return scene;
}

/// bench_collision_bvh's 300k-triangle loop (scale 2, ~300 triangles a box). Random boxes
/// at uniform loop parameters; drive: as bench_collision_bvh's BM_CarBoxQuery/.../1.
inline Scene loop_scene(std::size_t box_count) {
    const test::BankedLoop loop{2.0};
    Scene scene{"banked_loop_300k", loop.mesh(300000 / (2 * test::BankedLoop::kAcross)), {}, {}};
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (std::size_t i = 0; i < box_count; ++i) {
        const auto f = loop.frame(u(rng));
        scene.random_boxes.push_back(car_box(f.center, f.tangent, f.left, f.up));
    }
    const double loop_length = loop.scale * 1820.0;  // m, BankedLoop's perimeter
    for (std::size_t k = 0; k < box_count; ++k) {
        const auto f = loop.frame(std::fmod(0.37 + double(k) * kTravel / loop_length, 1.0));
        scene.drive_boxes.push_back(car_box(f.center, f.tangent, f.left, f.up));
    }
    return scene;
}

/// Bullet's view of the mesh: the arrays it reads (it does not copy them) and the shape.
struct BulletMesh {
    std::vector<int> indices;
    std::vector<btScalar> vertices;
    std::unique_ptr<btTriangleIndexVertexArray> arrays;
    std::unique_ptr<btBvhTriangleMeshShape> shape;
    double build_ms = 0;

    explicit BulletMesh(const TriangleMesh& mesh) {
        for (const auto& t : mesh.triangles)
            for (std::uint32_t k : t) indices.push_back(static_cast<int>(k));
        for (const glm::dvec3& v : mesh.vertices)
            for (int k = 0; k < 3; ++k) vertices.push_back(btScalar(v[k]));
        arrays = std::make_unique<btTriangleIndexVertexArray>(
            static_cast<int>(mesh.triangles.size()), indices.data(), int(3 * sizeof(int)),
            static_cast<int>(mesh.vertices.size()), vertices.data(), int(3 * sizeof(btScalar)));
        const auto start = Clock::now();
        shape = std::make_unique<btBvhTriangleMeshShape>(arrays.get(),
                                                         /*useQuantizedAabbCompression=*/true);
        build_ms = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
    }

    std::size_t node_bytes() const {
        btOptimizedBvh& bvh = *shape->getOptimizedBvh();
        return std::size_t(bvh.getQuantizedNodeArray().capacity()) * sizeof(btQuantizedBvhNode) +
               std::size_t(bvh.getSubtreeInfoArray().capacity()) * sizeof(btBvhSubtreeInfo) +
               std::size_t(bvh.getLeafNodeArray().capacity()) * sizeof(btQuantizedBvhNode);
    }
    std::size_t mesh_bytes() const {
        return indices.capacity() * sizeof(int) + vertices.capacity() * sizeof(btScalar);
    }
};

struct IndexCollector : btNodeOverlapCallback {
    std::vector<std::uint32_t>* out = nullptr;
    void processNode(int /*subPart*/, int triangle) override {
        out->push_back(static_cast<std::uint32_t>(triangle));
    }
};

/// Keeps the reported triangles whose own box overlaps the query box: Bullet's superset cut
/// down to the exact set ours returns, with the vertices Bullet fetches.
struct ExactTriangleCollector : btTriangleCallback {
    std::vector<std::uint32_t>* out = nullptr;
    btVector3 min, max;
    void processTriangle(btVector3* triangle, int /*part*/, int index) override {
        btVector3 lo = triangle[0], hi = triangle[0];
        for (int k = 1; k < 3; ++k) {
            lo.setMin(triangle[k]);
            hi.setMax(triangle[k]);
        }
        if (lo.x() <= max.x() && min.x() <= hi.x() && lo.y() <= max.y() && min.y() <= hi.y() &&
            lo.z() <= max.z() && min.z() <= hi.z())
            out->push_back(static_cast<std::uint32_t>(index));
    }
};

template <class Query>
double median_us(const std::vector<Aabb>& boxes, Query&& query) {
    std::vector<double> us;
    us.reserve(boxes.size());
    for (const Aabb& box : boxes) {
        const auto start = Clock::now();
        query(box);
        us.push_back(std::chrono::duration<double, std::micro>(Clock::now() - start).count());
    }
    std::nth_element(us.begin(), us.begin() + std::ptrdiff_t(us.size() / 2), us.end());
    return us[us.size() / 2];
}

/// How far the boxes are apart along their most separated axis (m, <= 0 when overlapping).
inline double gap(const Aabb& a, const Aabb& b) {
    const glm::dvec3 g = glm::max(a.min - b.max, b.min - a.max);
    return std::max({g.x, g.y, g.z});
}

struct SceneResult {
    std::string scene;
    std::size_t triangles = 0, boxes = 0;
    double ours_build_ms = 0, bullet_build_ms = 0;
    double ours_bytes_per_tri = 0, bullet_node_bytes_per_tri = 0, bullet_total_bytes_per_tri = 0;
    double ours_us = 0, bullet_nodes_us = 0, bullet_exact_us = 0;
    double ours_found_mean = 0, bullet_found_mean = 0;
    std::size_t missing = 0;      ///< triangles ours found and Bullet did not (must be 0)
    std::size_t extras = 0;       ///< triangles Bullet found and ours did not
    std::size_t ours_missed = 0;  ///< extras that overlap the box and ours keeps (must be 0)
    double extra_gap_max = 0;     ///< the farthest extra's box from the query box (m)
    double slack = 0;             ///< the quantisation slack the extras must stay within (m)
};

/// One box set on a built scene: times and the triangle-set check.
inline SceneResult run_boxes(const Scene& scene, const std::string& kind,
                             const std::vector<Aabb>& boxes, const StaticCollider& ours,
                             const BulletMesh& bullet, SceneResult r) {
    r.scene = scene.name + "/" + kind;
    r.boxes = boxes.size();
    std::vector<std::uint32_t> out;
    out.reserve(4096);
    r.ours_us = median_us(boxes, [&](const Aabb& box) {
        out.clear();
        ours.query_aabb(box, out);
    });
    const btOptimizedBvh* bvh = bullet.shape->getOptimizedBvh();
    IndexCollector nodes;
    nodes.out = &out;
    r.bullet_nodes_us = median_us(boxes, [&](const Aabb& box) {
        out.clear();
        bvh->reportAabbOverlappingNodex(&nodes, to_bullet(box.min), to_bullet(box.max));
    });
    ExactTriangleCollector triangles;
    triangles.out = &out;
    r.bullet_exact_us = median_us(boxes, [&](const Aabb& box) {
        out.clear();
        triangles.min = to_bullet(box.min);
        triangles.max = to_bullet(box.max);
        bullet.shape->processAllTriangles(&triangles, triangles.min, triangles.max);
    });

    // Same sets: ours within Bullet's; Bullet's extras within the quantisation slack. Its
    // grid spans the mesh box grown by 1 m on each side in 65534 steps; the query and a
    // leaf box each round outward by up to 2 steps; leaf boxes are at least 2 mm thick.
    Aabb bounds;
    for (const glm::dvec3& v : scene.mesh.vertices) bounds.expand(v);
    const glm::dvec3 step = (bounds.extent() + 2.0) / 65534.0;
    r.slack = 4.0 * std::max({step.x, step.y, step.z}) + 0.002;
    std::vector<std::uint32_t> mine, theirs;
    std::size_t ours_total = 0, bullet_total = 0;
    for (const Aabb& box : boxes) {
        mine.clear();
        theirs.clear();
        ours.query_aabb(box, mine);
        nodes.out = &theirs;
        bvh->reportAabbOverlappingNodex(&nodes, to_bullet(box.min), to_bullet(box.max));
        std::sort(mine.begin(), mine.end());
        std::sort(theirs.begin(), theirs.end());
        ours_total += mine.size();
        bullet_total += theirs.size();
        std::vector<std::uint32_t> difference;
        std::set_difference(mine.begin(), mine.end(), theirs.begin(), theirs.end(),
                            std::back_inserter(difference));
        r.missing += difference.size();
        difference.clear();
        std::set_difference(theirs.begin(), theirs.end(), mine.begin(), mine.end(),
                            std::back_inserter(difference));
        r.extras += difference.size();
        for (std::uint32_t t : difference) {
            Aabb tri;
            for (std::uint32_t v : scene.mesh.triangles[t]) tri.expand(scene.mesh.vertices[v]);
            r.extra_gap_max = std::max(r.extra_gap_max, gap(tri, box));
            // An extra whose own box overlaps the query is one ours should have found.
            r.ours_missed += gap(tri, box) <= 0.0 && ours.has_triangle(t);
        }
    }
    r.ours_found_mean = double(ours_total) / double(r.boxes);
    r.bullet_found_mean = double(bullet_total) / double(r.boxes);
    return r;
}

/// Builds both structures once (each build timed once) and runs both box sets.
inline void run_scene(const Scene& scene, std::vector<SceneResult>& results) {
    SceneResult r{scene.name, scene.mesh.triangles.size()};
    const auto start = Clock::now();
    const StaticCollider ours(scene.mesh);
    r.ours_build_ms = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
    const BulletMesh bullet(scene.mesh);
    r.bullet_build_ms = bullet.build_ms;
    r.ours_bytes_per_tri = double(ours.bytes_used()) / double(r.triangles);
    r.bullet_node_bytes_per_tri = double(bullet.node_bytes()) / double(r.triangles);
    r.bullet_total_bytes_per_tri =
        double(bullet.node_bytes() + bullet.mesh_bytes()) / double(r.triangles);
    results.push_back(run_boxes(scene, "random", scene.random_boxes, ours, bullet, r));
    results.push_back(run_boxes(scene, "drive", scene.drive_boxes, ours, bullet, r));
}

}  // namespace trackphys::peers
