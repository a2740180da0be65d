#include "trackphys/geometry/mesh_chunks.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <string>
#include <utility>

#include "geometry/mesh_surface_check.hpp"
#include "trackphys/error.hpp"

namespace trackphys {

std::vector<TriangleMesh> split_into_chunks(const TriangleMesh& mesh, double cell_m) {
    if (!(std::isfinite(cell_m) && cell_m > 0.0))
        throw Error("chunk size must be finite and > 0 m, got " + exact_text(cell_m));
    // The cell of each triangle, clamped so that far or non-finite centroids still get one
    // (the collider then names the bad vertex).
    auto cell_of = [cell_m](double x) {
        const double c = std::floor(x / cell_m);
        constexpr double kLimit = 1e15;
        return static_cast<std::int64_t>(std::isnan(c) ? 0.0 : std::clamp(c, -kLimit, kLimit));
    };
    detail::check_surface_count(mesh);
    const bool labelled = !mesh.surfaces.empty();
    std::map<std::pair<std::int64_t, std::int64_t>, std::vector<std::uint32_t>> cells;
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
        glm::dvec3 centroid(0.0);
        for (const std::uint32_t v : mesh.triangles[t]) {
            if (v >= mesh.vertices.size())
                throw Error("triangle " + std::to_string(t) + ": vertex index " +
                            std::to_string(v) + " out of range (" +
                            std::to_string(mesh.vertices.size()) + " vertices)");
            centroid += mesh.vertices[v] / 3.0;
        }
        cells[{cell_of(centroid.x), cell_of(centroid.z)}].push_back(static_cast<std::uint32_t>(t));
    }
    constexpr std::uint32_t kUnused = std::numeric_limits<std::uint32_t>::max();
    std::vector<std::uint32_t> remap(mesh.vertices.size(), kUnused);
    std::vector<TriangleMesh> chunks;
    chunks.reserve(cells.size());
    for (const auto& [cell, triangles] : cells) {
        TriangleMesh& chunk = chunks.emplace_back();
        chunk.triangles.reserve(triangles.size());
        for (const std::uint32_t t : triangles) {
            std::array<std::uint32_t, 3> local;
            for (int k = 0; k < 3; ++k) {
                std::uint32_t& r = remap[mesh.triangles[t][k]];
                if (r == kUnused) {
                    r = static_cast<std::uint32_t>(chunk.vertices.size());
                    chunk.vertices.push_back(mesh.vertices[mesh.triangles[t][k]]);
                }
                local[k] = r;
            }
            chunk.triangles.push_back(local);
            if (labelled) chunk.surfaces.push_back(mesh.surfaces[t]);
        }
        for (const std::uint32_t t : triangles)
            for (const std::uint32_t v : mesh.triangles[t]) remap[v] = kUnused;
    }
    return chunks;
}

}  // namespace trackphys
