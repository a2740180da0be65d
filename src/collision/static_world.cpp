#include "trackphys/collision/static_world.hpp"

#include <cmath>
#include <limits>
#include <string>

#include "trackphys/error.hpp"
#include "trackphys/math/types.hpp"
#include "triangle_predicates.hpp"

namespace trackphys {

Aabb swept_box(const Aabb& box, const glm::dvec3& displacement, double margin) {
    if (!is_finite(displacement) || !std::isfinite(margin) || !(margin >= 0.0))
        throw Error(
            "swept_box: displacement must be finite and margin finite and >= 0, got "
            "margin " +
            std::to_string(margin));
    Aabb swept = box;
    swept.expand(Aabb{box.min + displacement, box.max + displacement});
    return swept.padded(margin);
}

std::uint32_t StaticWorld::add(std::shared_ptr<const StaticCollider> collider) {
    if (!collider) throw Error("StaticWorld::add: the collider is null");
    if (colliders_.size() >= std::numeric_limits<std::uint32_t>::max())
        throw Error("StaticWorld::add: too many colliders");
    bounds_.push_back(collider->bounds());
    colliders_.push_back(std::move(collider));
    return static_cast<std::uint32_t>(colliders_.size() - 1);
}

const StaticCollider& StaticWorld::collider(std::uint32_t id) const {
    if (id >= colliders_.size())
        throw Error("StaticWorld: no collider " + std::to_string(id) + " (the world has " +
                    std::to_string(colliders_.size()) + ")");
    return *colliders_[id];
}

void StaticWorld::query_aabb(const Aabb& box, std::vector<TriangleRef>& out) const {
    for (std::size_t i = 0; i < colliders_.size(); ++i)
        if (bounds_[i].overlaps(box))
            colliders_[i]->query_aabb_refs(box, static_cast<std::uint32_t>(i), out);
}

std::optional<WorldRayHit> StaticWorld::raycast(const glm::dvec3& origin,
                                                const glm::dvec3& unit_dir,
                                                double max_distance) const {
    const collision_detail::RayQuery ray =
        collision_detail::make_ray_query(origin, unit_dir, max_distance);
    std::optional<WorldRayHit> best;
    double limit = ray.max_distance;
    for (std::size_t i = 0; i < colliders_.size(); ++i) {
        double t_near, t_far;
        if (bounds_[i].empty() || !collision_detail::ray_box_span(
                                      ray, bounds_[i].min, bounds_[i].max, limit, t_near, t_far))
            continue;
        // Searching up to the best distance so far; only a strictly nearer hit replaces it.
        const std::optional<RayHit> hit = colliders_[i]->raycast(origin, unit_dir, limit);
        if (hit && (!best || hit->distance < limit)) {
            limit = hit->distance;
            best = WorldRayHit{static_cast<std::uint32_t>(i), *hit};
        }
    }
    return best;
}

}  // namespace trackphys
