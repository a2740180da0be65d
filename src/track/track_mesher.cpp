#include "track/track_mesher.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include <glm/geometric.hpp>

#include "trackphys/assert.hpp"

namespace trackphys::track_detail {

std::vector<glm::dvec3> cross_section(const CenterlineSample& sample, const TrackParams& params) {
    const glm::dvec3 up_world(0.0, 1.0, 0.0);
    // Horizontal left, for the walls: +Y x tangent, flattened.
    const glm::dvec3 left_flat =
        glm::normalize(glm::dvec3(sample.tangent.z, 0.0, -sample.tangent.x));
    const glm::dvec3 wall_up = params.wall_height_m * up_world;
    const glm::dvec3 thickness = params.wall_thickness_m * left_flat;

    std::vector<glm::dvec3> points;
    points.reserve(cross_section_size(params));
    const glm::dvec3 left_base = sample.position + (0.5 * params.width_m) * sample.left;
    points.push_back(left_base + thickness);
    points.push_back(left_base + thickness + wall_up);
    points.push_back(left_base + wall_up);
    for (int j = 0; j <= params.strips; ++j) {
        // Across from +w/2 (left) to -w/2 (right); the middle point is the centreline itself.
        const double offset = params.width_m * (0.5 - static_cast<double>(j) / params.strips);
        points.push_back(sample.position + offset * sample.left);
    }
    const glm::dvec3 right_base = points.back();
    points.push_back(right_base + wall_up);
    points.push_back(right_base - thickness + wall_up);
    points.push_back(right_base - thickness);
    return points;
}

std::vector<TrackChunk> build_chunks(const std::vector<CenterlineSample>& rows, double length_m,
                                     const TrackParams& params) {
    const std::size_t row_count = rows.size();
    const std::size_t width = cross_section_size(params);
    // Every row's cross-section once; chunks copy them, so a shared boundary row is
    // bit-identical in both chunks, and the closing row is row 0's.
    std::vector<std::vector<glm::dvec3>> sections(row_count);
    for (std::size_t r = 0; r < row_count; ++r) sections[r] = cross_section(rows[r], params);

    // Chunk c starts at the first row at or past c * length / count.
    const auto count =
        static_cast<std::size_t>(std::max(1L, std::lround(length_m / params.chunk_length_m)));
    std::vector<std::size_t> start(count + 1, row_count);
    std::size_t r = 0;
    for (std::size_t c = 0; c < count; ++c) {
        const double from = length_m * static_cast<double>(c) / static_cast<double>(count);
        while (r < row_count && rows[r].distance < from) ++r;
        start[c] = r;
    }

    std::vector<TrackChunk> chunks(count);
    for (std::size_t c = 0; c < count; ++c) {
        const std::size_t first = start[c];
        const std::size_t last = start[c + 1];  // inclusive; row_count means row 0
        TP_ASSERT(last > first, "every chunk holds at least one row step");
        TrackChunk& chunk = chunks[c];
        chunk.first_sample = first;
        TriangleMesh& mesh = chunk.mesh;
        mesh.vertices.reserve((last - first + 1) * width);
        for (std::size_t row = first; row <= last; ++row) {
            for (const glm::dvec3& p : sections[row % row_count]) {
                mesh.vertices.push_back(p);
                chunk.bounds.expand(p);
            }
        }
        // Quad (k, k+1) between local rows i and i+1 as triangles (a, b, c), (a, c, d) with
        // a = (i, k), b = (i, k+1), c = (i+1, k+1), d = (i+1, k): both share the quad's
        // winding, so their normals are (p[k+1] - p[k]) x tangent (see cross_section).
        const auto add_quads = [&](std::size_t k_begin, std::size_t k_end) {
            for (std::size_t i = 0; i < last - first; ++i) {
                for (std::size_t k = k_begin; k < k_end; ++k) {
                    const auto a = static_cast<std::uint32_t>(i * width + k);
                    const auto b = static_cast<std::uint32_t>(i * width + k + 1);
                    const auto cc = static_cast<std::uint32_t>((i + 1) * width + k + 1);
                    const auto d = static_cast<std::uint32_t>((i + 1) * width + k);
                    mesh.triangles.push_back({a, b, cc});
                    mesh.triangles.push_back({a, cc, d});
                }
            }
        };
        const std::size_t road_end = kFirstRoadPoint + static_cast<std::size_t>(params.strips);
        add_quads(kFirstRoadPoint, road_end);
        chunk.road_triangle_count = mesh.triangles.size();
        add_quads(0, kFirstRoadPoint);
        add_quads(road_end, width - 1);
        mesh.surfaces.assign(mesh.triangles.size(), kWallSurface);
        std::fill_n(mesh.surfaces.begin(), chunk.road_triangle_count, kRoadSurface);
    }
    return chunks;
}

}  // namespace trackphys::track_detail
