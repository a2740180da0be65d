#include "trackphys/collision/brute_force_collider.hpp"

#include <limits>

#include "triangle_predicates.hpp"

namespace trackphys {

BruteForceCollider::BruteForceCollider(const TriangleMesh& mesh)
    : mesh_(mesh), kept_(collision_detail::validate_and_keep(mesh)) {}

void BruteForceCollider::query_aabb(const Aabb& box, std::vector<std::uint32_t>& out) const {
    for (const std::uint32_t t : kept_) {
        const auto& tri = mesh_.triangles[t];
        if (collision_detail::triangle_box(mesh_.vertices[tri[0]], mesh_.vertices[tri[1]],
                                           mesh_.vertices[tri[2]])
                .overlaps(box))
            out.push_back(t);
    }
}

void BruteForceCollider::query_sphere(const glm::dvec3& center, double radius,
                                      std::vector<std::uint32_t>& out) const {
    const auto q = collision_detail::make_capsule_query(center, center, radius);
    for (const std::uint32_t t : kept_) {
        const auto& tri = mesh_.triangles[t];
        if (collision_detail::sphere_keeps(q, mesh_.vertices[tri[0]], mesh_.vertices[tri[1]],
                                           mesh_.vertices[tri[2]]))
            out.push_back(t);
    }
}

void BruteForceCollider::query_capsule(const glm::dvec3& start, const glm::dvec3& end,
                                       double radius, std::vector<std::uint32_t>& out) const {
    const auto q = collision_detail::make_capsule_query(start, end, radius);
    for (const std::uint32_t t : kept_) {
        const auto& tri = mesh_.triangles[t];
        if (collision_detail::capsule_keeps(q, mesh_.vertices[tri[0]], mesh_.vertices[tri[1]],
                                            mesh_.vertices[tri[2]]))
            out.push_back(t);
    }
}

std::optional<RayHit> BruteForceCollider::raycast(const glm::dvec3& origin,
                                                  const glm::dvec3& unit_dir,
                                                  double max_distance) const {
    const auto ray = collision_detail::make_ray_query(origin, unit_dir, max_distance);
    std::optional<RayHit> best;
    double best_t = ray.max_distance;
    std::uint32_t best_triangle = std::numeric_limits<std::uint32_t>::max();
    for (const std::uint32_t t : kept_) {
        const auto& tri = mesh_.triangles[t];
        const glm::dvec3& a = mesh_.vertices[tri[0]];
        const glm::dvec3& b = mesh_.vertices[tri[1]];
        const glm::dvec3& c = mesh_.vertices[tri[2]];
        const std::optional<double> hit = collision_detail::ray_triangle(ray, a, b, c);
        if (hit && collision_detail::better_hit(*hit, t, best_t, best_triangle)) {
            best_t = *hit;
            best_triangle = t;
            best = RayHit{*hit, t, collision_detail::unit_normal(a, b, c)};
        }
    }
    return best;
}

}  // namespace trackphys
