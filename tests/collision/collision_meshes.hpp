#pragma once

// Meshes for the collision tests and benchmarks (header-only; the benchmarks include it
// too). banked_loop_mesh is a stand-in for the Bezier track generator: small on purpose.

#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "trackphys/geometry/aabb.hpp"
#include "trackphys/geometry/triangle_mesh.hpp"

namespace trackphys::test {

/// n independent triangles (no shared vertices), centers uniform in a 200 m cube, edge
/// sizes log-uniform between 5 cm and 20 m.
inline TriangleMesh random_soup(std::size_t n, std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> center(-100.0, 100.0), unit(-1.0, 1.0),
        log_size(std::log(0.05), std::log(20.0));
    TriangleMesh mesh;
    for (std::size_t i = 0; i < n; ++i) {
        const glm::dvec3 c(center(rng), center(rng), center(rng));
        const double size = std::exp(log_size(rng));
        const auto base = static_cast<std::uint32_t>(mesh.vertices.size());
        for (int k = 0; k < 3; ++k)
            mesh.vertices.push_back(c + glm::dvec3(unit(rng), unit(rng), unit(rng)) * size);
        mesh.triangles.push_back({base, base + 1, base + 2});
    }
    return mesh;
}

/// The hard cases: a grid of integer-coordinate squares sharing edges and vertices (rays
/// through shared edges and vertices, float-exact bounds), the same triangles again with
/// fresh vertices and again with the same indices (duplicates), kilometre-sized
/// triangles, slivers, and degenerate ones (repeated vertex, collinear, zero area far from
/// the origin). Returns the mesh; *degenerate gets the number of degenerate triangles.
inline TriangleMesh nasty_mesh(std::uint64_t seed, std::size_t* degenerate = nullptr) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    TriangleMesh mesh;
    auto add = [&mesh](const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
        const auto base = static_cast<std::uint32_t>(mesh.vertices.size());
        mesh.vertices.insert(mesh.vertices.end(), {a, b, c});
        mesh.triangles.push_back({base, base + 1, base + 2});
    };
    // 20 x 20 grid of unit squares in the plane y = 0, shared vertices, two triangles each.
    constexpr std::uint32_t kGrid = 20;
    for (std::uint32_t i = 0; i <= kGrid; ++i)
        for (std::uint32_t j = 0; j <= kGrid; ++j)
            mesh.vertices.emplace_back(double(i) - 10.0, 0.0, double(j) - 10.0);
    const std::size_t grid_triangles_begin = mesh.triangles.size();
    for (std::uint32_t i = 0; i < kGrid; ++i)
        for (std::uint32_t j = 0; j < kGrid; ++j) {
            const std::uint32_t v = i * (kGrid + 1) + j;
            mesh.triangles.push_back({v, v + 1, v + kGrid + 1});
            mesh.triangles.push_back({v + 1, v + kGrid + 2, v + kGrid + 1});
        }
    const std::size_t grid_triangles_end = mesh.triangles.size();
    // Duplicates: every 7th grid triangle with the same indices, and with copied vertices.
    for (std::size_t t = grid_triangles_begin; t < grid_triangles_end; t += 7) {
        const auto tri = mesh.triangles[t];
        mesh.triangles.push_back(tri);
        add(mesh.vertices[tri[0]], mesh.vertices[tri[1]], mesh.vertices[tri[2]]);
    }
    // A vertical wall of integer squares crossing the grid (x = 0.5 plane).
    for (int i = 0; i < 10; ++i) {
        const double z = i - 5.0;
        add({0.5, -2.0, z}, {0.5, 2.0, z}, {0.5, -2.0, z + 1.0});
        add({0.5, 2.0, z}, {0.5, 2.0, z + 1.0}, {0.5, -2.0, z + 1.0});
    }
    // Huge triangles (kilometres) through the scene, and slivers.
    for (int i = 0; i < 40; ++i) {
        add(glm::dvec3(unit(rng), unit(rng), unit(rng)) * 3000.0,
            glm::dvec3(unit(rng), unit(rng), unit(rng)) * 3000.0,
            glm::dvec3(unit(rng), unit(rng), unit(rng)) * 3000.0);
        const glm::dvec3 a(unit(rng) * 10, unit(rng) * 10, unit(rng) * 10);
        const glm::dvec3 b = a + glm::dvec3(unit(rng), unit(rng), unit(rng)) * 5.0;
        add(a, b, 0.5 * (a + b) + glm::dvec3(0.0, 1e-9 * (1 + i), 0.0));
    }
    // Degenerate: repeated vertex, collinear, and a zero-area triangle far away.
    std::size_t degenerate_count = 0;
    for (int i = 0; i < 30; ++i) {
        const glm::dvec3 a(unit(rng) * 10, unit(rng) * 10, unit(rng) * 10);
        const glm::dvec3 b(unit(rng) * 10, unit(rng) * 10, unit(rng) * 10);
        add(a, a, b);
        add(a, b, a + (b - a) * 0.25);
        add(glm::dvec3(1e5, 0, 0) + a, glm::dvec3(1e5, 0, 0) + a, glm::dvec3(1e5, 0, 0) + a);
        degenerate_count += 3;
    }
    // Shared-index degenerate: two corners on one vertex.
    mesh.triangles.push_back({0, 0, 1});
    ++degenerate_count;
    if (degenerate) *degenerate = degenerate_count;
    return mesh;
}

/// A banked track stand-in: a closed loop around an ellipse (scale * 400 m x 150 m half
/// axes, the tightest turn radius scale * 56 m at the ends), rolling scale * 10 m up and
/// down, banked up to 25 deg in the turns; a 12 m road between two 1 m walls. `segments`
/// cross-sections evenly spaced along the loop (scale * 1.82 km), 24 quads across (20 road,
/// 2 per wall): 48 * segments triangles sharing vertices.
struct BankedLoop {
    static constexpr double kHalfX = 400.0, kHalfZ = 150.0, kRoadWidth = 12.0, kWallHeight = 1.0;
    static constexpr std::uint32_t kAcross = 24;

    double scale = 1.0;

    /// Frame of the road at loop parameter u in [0, 1): center line point, unit tangent,
    /// banked left (in the road surface) and banked up (road normal).
    struct Frame {
        glm::dvec3 center, tangent, left, up;
    };
    Frame frame(double u) const {
        const double theta = 2.0 * std::numbers::pi * u;
        Frame f;
        f.center = glm::dvec3(kHalfX * std::cos(theta), 10.0 * std::sin(2.0 * theta),
                              kHalfZ * std::sin(theta)) *
                   scale;
        f.tangent = glm::normalize(glm::dvec3(
            -kHalfX * std::sin(theta), 20.0 * std::cos(2.0 * theta), kHalfZ * std::cos(theta)));
        const glm::dvec3 flat_left = glm::normalize(glm::cross(glm::dvec3(0, 1, 0), f.tangent));
        const glm::dvec3 flat_up = glm::cross(f.tangent, flat_left);
        // Bank toward the inside of the turn, strongest at the tight ends (theta = 0, pi).
        const double c = std::cos(theta);
        const double bank = 25.0 * std::numbers::pi / 180.0 * c * c * c * c;
        f.left = flat_left * std::cos(bank) + flat_up * std::sin(bank);
        f.up = glm::cross(f.tangent, f.left);
        return f;
    }

    /// Loop parameters of `segments` cross-sections evenly spaced by arc length (as a track
    /// generator would place them), from a piecewise-linear length table.
    std::vector<double> even_parameters(std::uint32_t segments) const {
        constexpr int kTable = 4096;
        std::vector<double> length(kTable + 1, 0.0);
        for (int k = 1; k <= kTable; ++k)
            length[k] = length[k - 1] + glm::distance(frame(double(k) / kTable).center,
                                                      frame(double(k - 1) / kTable).center);
        std::vector<double> u(segments);
        int k = 0;
        for (std::uint32_t i = 0; i < segments; ++i) {
            const double target = length[kTable] * i / segments;
            while (length[k + 1] < target) ++k;
            u[i] = (k + (target - length[k]) / (length[k + 1] - length[k])) / kTable;
        }
        return u;
    }

    TriangleMesh mesh(std::uint32_t segments) const {
        TriangleMesh m;
        m.vertices.reserve(std::size_t{segments} * (kAcross + 1));
        m.triangles.reserve(std::size_t{segments} * kAcross * 2);
        const std::vector<double> parameters = even_parameters(segments);
        for (std::uint32_t i = 0; i < segments; ++i) {
            const Frame f = frame(parameters[i]);
            const double half = 0.5 * kRoadWidth;
            for (std::uint32_t k = 0; k <= kAcross; ++k) {
                glm::dvec3 p;
                if (k <= 2) {  // left wall, top down
                    p = f.center + f.left * half + f.up * (kWallHeight * (2 - k) / 2.0);
                } else if (k >= kAcross - 2) {  // right wall, bottom up
                    p = f.center - f.left * half + f.up * (kWallHeight * (k - (kAcross - 2)) / 2.0);
                } else {
                    const double s = double(k - 2) / (kAcross - 4);
                    p = f.center + f.left * (half - s * kRoadWidth);
                }
                m.vertices.push_back(p);
            }
        }
        for (std::uint32_t i = 0; i < segments; ++i) {
            const std::uint32_t a = i * (kAcross + 1), b = ((i + 1) % segments) * (kAcross + 1);
            for (std::uint32_t k = 0; k < kAcross; ++k) {
                m.triangles.push_back({a + k, a + k + 1, b + k});
                m.triangles.push_back({a + k + 1, b + k + 1, b + k});
            }
        }
        return m;
    }

    /// A car's swept, padded box at loop parameter u: a 4.5 x 1.2 x 2 m box (length along
    /// the tangent, height along the road normal) resting on the road, moved `travel` m
    /// along the tangent and padded by `margin` m.
    Aabb car_box(double u, double travel, double margin) const {
        const Frame f = frame(u);
        const glm::dvec3 half_extent =
            glm::abs(f.tangent) * 2.25 + glm::abs(f.up) * 0.6 + glm::abs(f.left) * 1.0;
        const glm::dvec3 center = f.center + f.up * 0.6;
        Aabb box{center - half_extent, center + half_extent};
        box.expand(Aabb{box.min + f.tangent * travel, box.max + f.tangent * travel});
        return box.padded(margin);
    }
};

}  // namespace trackphys::test
