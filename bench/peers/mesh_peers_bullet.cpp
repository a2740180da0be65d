// Bullet's btBvhTriangleMeshShape against our StaticCollider on the same meshes and padded
// car boxes: the scenes, queries and checks are peers/mesh_peer_harness.hpp; this program
// prints them as a table and JSON. Built twice (float and double btScalar), as the contact
// peer.
//
//   build/release/bench/bench_peers_mesh_bullet_float [--quick] [--json FILE]

#include <cstdio>
#include <string>
#include <string_view>
#include <vector>

#include "peers/mesh_peer_harness.hpp"

namespace {

using namespace trackphys::peers;

void print(const std::vector<SceneResult>& results) {
    std::printf(
        "%-27s %7s %6s | %8s %8s | %6s %8s %7s | %6s %7s %8s %6s %7s | %6s %6s %6s %4s "
        "%7s %6s\n",
        "scene", "tris", "boxes", "build_ms", "bt_ms", "B/tri", "bt_nodeB", "bt_allB", "us",
        "bt_node", "bt_exact", "x_node", "x_exact", "found", "bt_fnd", "extras", "miss", "gap_max",
        "slack");
    for (const SceneResult& r : results)
        std::printf(
            "%-27s %7zu %6zu | %8.1f %8.1f | %6.1f %8.1f %7.1f | %6.2f %7.2f %8.2f "
            "%6.2f %7.2f | %6.1f %6.1f %6zu %4zu %7.4f %6.4f\n",
            r.scene.c_str(), r.triangles, r.boxes, r.ours_build_ms, r.bullet_build_ms,
            r.ours_bytes_per_tri, r.bullet_node_bytes_per_tri, r.bullet_total_bytes_per_tri,
            r.ours_us, r.bullet_nodes_us, r.bullet_exact_us, r.bullet_nodes_us / r.ours_us,
            r.bullet_exact_us / r.ours_us, r.ours_found_mean, r.bullet_found_mean, r.extras,
            r.missing + r.ours_missed, r.extra_gap_max, r.slack);
}

bool write_json(const std::string& path, const char* program,
                const std::vector<SceneResult>& results) {
    std::FILE* f = std::fopen(path.c_str(), "w");
    if (!f) {
        std::fprintf(stderr, "%s: cannot write '%s'\n", program, path.c_str());
        return false;
    }
    std::fprintf(f, "{\n  \"program\": \"%s\",\n  \"kind\": \"mesh_box_query\",\n", program);
    std::fprintf(f, "  \"results\": [\n");
    for (std::size_t i = 0; i < results.size(); ++i) {
        const SceneResult& r = results[i];
        std::fprintf(f,
                     "    {\"scene\": \"%s\", \"triangles\": %zu, \"boxes\": %zu, "
                     "\"ours_build_ms\": %.6g, \"bullet_build_ms\": %.6g, "
                     "\"ours_bytes_per_triangle\": %.6g, \"bullet_node_bytes_per_triangle\": %.6g, "
                     "\"bullet_total_bytes_per_triangle\": %.6g, \"ours_median_us\": %.6g, "
                     "\"bullet_nodes_median_us\": %.6g, \"bullet_exact_median_us\": %.6g, "
                     "\"ours_found_mean\": %.6g, \"bullet_found_mean\": %.6g, \"missing\": %zu, "
                     "\"extras\": %zu, \"ours_missed\": %zu, \"extra_gap_max_m\": %.6g, "
                     "\"slack_m\": %.6g}%s\n",
                     r.scene.c_str(), r.triangles, r.boxes, r.ours_build_ms, r.bullet_build_ms,
                     r.ours_bytes_per_tri, r.bullet_node_bytes_per_tri,
                     r.bullet_total_bytes_per_tri, r.ours_us, r.bullet_nodes_us, r.bullet_exact_us,
                     r.ours_found_mean, r.bullet_found_mean, r.missing, r.extras, r.ours_missed,
                     r.extra_gap_max, r.slack, i + 1 < results.size() ? "," : "");
    }
    std::fprintf(f, "  ]\n}\n");
    return std::fclose(f) == 0;
}

}  // namespace

int main(int argc, char** argv) {
#ifdef BT_USE_DOUBLE_PRECISION
    const char* program = "bench_peers_mesh_bullet_double";
#else
    const char* program = "bench_peers_mesh_bullet_float";
#endif
    bool quick = false;
    std::string json;
    for (int i = 1; i < argc; ++i) {
        const std::string_view arg = argv[i];
        if (arg == "--quick") {
            quick = true;
        } else if (arg == "--json" && i + 1 < argc) {
            json = argv[++i];
        } else {
            std::fprintf(stderr, "%s: unknown argument '%s'\nusage: %s [--quick] [--json FILE]\n",
                         program, argv[i], program);
            return 2;
        }
    }
    const std::size_t boxes = quick ? 500 : 10000;
    std::vector<SceneResult> results;
    for (const Scene& scene : {track_scene(boxes), loop_scene(boxes)}) {
        std::fprintf(stderr, "%s: %s (%zu triangles, %zu boxes a set)\n", program,
                     scene.name.c_str(), scene.mesh.triangles.size(), boxes);
        run_scene(scene, results);
    }
    print(results);
    bool ok = true;
    for (const SceneResult& r : results)
        if (r.missing > 0 || r.ours_missed > 0 || r.extra_gap_max > r.slack) {
            std::fprintf(stderr, "%s: %s: triangle sets differ beyond quantisation\n", program,
                         r.scene.c_str());
            ok = false;
        }
    if (!json.empty()) ok = write_json(json, program, results) && ok;
    return ok ? 0 : 1;
}
