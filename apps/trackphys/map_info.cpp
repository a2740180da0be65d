#include "map_info.hpp"

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <span>
#include <vector>

#include <nlohmann/json.hpp>

#include "json_file.hpp"
#include "trackphys/io/map_file.hpp"

namespace trackphys::cli {
namespace {

// Sums over the colliders, and the figures per kept triangle.
struct MapFigures {
    std::size_t colliders = 0, triangles = 0, kept = 0, collider_bytes = 0, tree_bytes = 0;
    std::uintmax_t file_bytes = 0;
    double load_ms = 0.0;

    double per_triangle(double bytes) const { return kept > 0 ? bytes / double(kept) : 0.0; }
};

// The kept triangles of each surface id (what --surface-grips indexes; a map keeps the ids,
// not the mesh's material names).
std::vector<std::size_t> triangles_per_surface(const StaticWorld& statics) {
    std::vector<std::size_t> counts(1, 0);
    for (std::uint32_t id = 0; id < statics.size(); ++id) {
        const StaticCollider& collider = statics.collider(id);
        const std::span<const SurfaceId> surfaces = collider.surfaces();
        if (surfaces.empty()) {
            counts[0] += collider.triangle_count();
            continue;
        }
        for (std::uint32_t t = 0; t < surfaces.size(); ++t) {
            if (!collider.has_triangle(t)) continue;
            if (surfaces[t] >= counts.size()) counts.resize(std::size_t{surfaces[t]} + 1, 0);
            ++counts[surfaces[t]];
        }
    }
    return counts;
}

}  // namespace

void print_map_info(const std::string& file, bool json) {
    const auto start = std::chrono::steady_clock::now();
    const StaticMap map = load_static_world(file, std::nullopt);
    MapFigures f;
    f.load_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    f.file_bytes = std::filesystem::file_size(file);
    f.colliders = map.statics->size();
    Aabb bounds;
    for (std::uint32_t id = 0; id < f.colliders; ++id) {
        const StaticCollider& c = map.statics->collider(id);
        f.triangles += c.mesh_triangle_count();
        f.kept += c.triangle_count();
        f.collider_bytes += c.bytes_used();
        f.tree_bytes += map.plane_trees[id]->bytes_used();
        bounds.expand(c.bounds());
    }
    const std::vector<std::size_t> surfaces = triangles_per_surface(*map.statics);
    const PlaneTreeSettings& s = map.plane_tree_settings;
    const char* rule = s.rule == PlaneSplitRule::cost_based ? "cost_based" : "pca_median";
    if (json) {
        nlohmann::json out = {
            {"file", file},
            {"format_version", kMapFormatVersion},
            {"plane_tree_options",
             {{"rule", rule},
              {"max_leaf_size", s.max_leaf_size},
              {"query_radius", s.query_radius},
              {"node_cost", s.node_cost},
              {"slab_thickness", s.slab_thickness}}},
            {"colliders", f.colliders},
            {"triangles", f.triangles},
            {"kept_triangles", f.kept},
            {"bounds", {{"min", json_of(bounds.min)}, {"max", json_of(bounds.max)}}},
            {"file_bytes", f.file_bytes},
            {"collider_bytes", f.collider_bytes},
            {"plane_tree_bytes", f.tree_bytes},
            {"load_ms", f.load_ms},
            {"surfaces", nlohmann::json::array()},
        };
        for (std::size_t id = 0; id < surfaces.size(); ++id)
            out["surfaces"].push_back({{"id", id}, {"triangles", surfaces[id]}});
        if (map.track)
            out["track"] = {{"seed", map.track->params.seed},
                            {"length_m", map.track->length_m},
                            {"centerline_samples", map.track->centerline.size()}};
        std::printf("%s\n", report_text(out).c_str());
        return;
    }
    std::printf("%-20s %s\n", "file", file.c_str());
    std::printf("%-20s trackphys map, format version %u\n", "format", kMapFormatVersion);
    std::printf("%-20s %s, max leaf %d, query radius %g m, node cost %g, slab %g m\n",
                "plane trees", rule, s.max_leaf_size, s.query_radius, s.node_cost,
                s.slab_thickness);
    std::printf("%-20s %zu\n", "colliders", f.colliders);
    std::printf("%-20s %zu (%zu kept)\n", "triangles", f.triangles, f.kept);
    std::printf("%-20s %.3f %.3f %.3f m\n", "bounds min", bounds.min.x, bounds.min.y, bounds.min.z);
    std::printf("%-20s %.3f %.3f %.3f m\n", "bounds max", bounds.max.x, bounds.max.y, bounds.max.z);
    if (map.track)
        std::printf("%-20s seed %llu, %.3f m, %zu centreline samples\n", "track",
                    static_cast<unsigned long long>(map.track->params.seed), map.track->length_m,
                    map.track->centerline.size());
    else
        std::printf("%-20s none (baked from a mesh: drive it with --spawn)\n", "track");
    for (std::size_t id = 0; id < surfaces.size(); ++id)
        std::printf("%-20s %zu: %zu triangles\n", id == 0 ? "surfaces" : "", id, surfaces[id]);
    std::printf("%-20s %.1f MB, %.1f bytes a triangle\n", "file", double(f.file_bytes) / 1e6,
                f.per_triangle(double(f.file_bytes)));
    std::printf("%-20s %.1f MB, %.1f bytes a triangle\n", "colliders in memory",
                double(f.collider_bytes) / 1e6, f.per_triangle(double(f.collider_bytes)));
    std::printf("%-20s %.1f MB, %.1f bytes a triangle\n", "plane trees in memory",
                double(f.tree_bytes) / 1e6, f.per_triangle(double(f.tree_bytes)));
    std::printf("%-20s %.1f ms\n", "load", f.load_ms);
}

}  // namespace trackphys::cli
