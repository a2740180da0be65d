#pragma once

#include <concepts>
#include <cstdint>
#include <optional>
#include <vector>

#include <glm/vec3.hpp>

#include "trackphys/collision/static_collider.hpp"
#include "trackphys/export.hpp"
#include "trackphys/geometry/aabb.hpp"
#include "trackphys/geometry/triangle_mesh.hpp"
#include "trackphys/math/types.hpp"

namespace trackphys {

/// The queries a static triangle set answers; StaticCollider and its brute-force twin both
/// provide them with the same meaning (see StaticCollider), so tests and benchmarks can
/// run either.
template <class T>
concept TriangleQuerySource = requires(const T& c, const Aabb& box, const glm::dvec3& p, double r,
                                       std::vector<std::uint32_t>& out) {
    c.query_aabb(box, out);
    c.query_sphere(p, r, out);
    c.query_capsule(p, p, r, out);
    { c.raycast(p, p, r) } -> std::same_as<std::optional<RayHit>>;
};

/// The reference for StaticCollider: the same validation, the same kept triangles and the
/// same per-triangle predicates, applied to every triangle in mesh order. O(n) a query;
/// for tests and benchmarks.
class TRACKPHYS_API BruteForceCollider {
  public:
    /// Validates like StaticCollider (same errors) and keeps a copy of the mesh.
    explicit BruteForceCollider(const TriangleMesh& mesh);

    void query_aabb(const Aabb& box, std::vector<std::uint32_t>& out) const;
    void query_sphere(const glm::dvec3& center, double radius,
                      std::vector<std::uint32_t>& out) const;
    void query_capsule(const glm::dvec3& start, const glm::dvec3& end, double radius,
                       std::vector<std::uint32_t>& out) const;
    std::optional<RayHit> raycast(const glm::dvec3& origin, const glm::dvec3& unit_dir,
                                  double max_distance) const;

    /// Number of non-degenerate triangles.
    std::size_t triangle_count() const { return kept_.size(); }

  private:
    TriangleMesh mesh_;
    std::vector<std::uint32_t> kept_;  ///< non-degenerate triangles, mesh order
};

static_assert(TriangleQuerySource<StaticCollider>);
static_assert(TriangleQuerySource<BruteForceCollider>);

}  // namespace trackphys
