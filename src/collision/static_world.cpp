#include "trackphys/collision/static_world.hpp"

#include <atomic>
#include <cmath>
#include <limits>
#include <mutex>
#include <string>

#include "collider_tree.hpp"
#include "trackphys/error.hpp"
#include "trackphys/math/types.hpp"
#include "triangle_predicates.hpp"

namespace trackphys {

Aabb swept_box(const Aabb& box, const glm::dvec3& displacement, double margin) {
    if (!is_finite(displacement) || !std::isfinite(margin) || !(margin >= 0.0))
        throw Error(
            "swept_box: displacement must be finite and margin finite and >= 0, got "
            "margin " +
            exact_text(margin));
    Aabb swept = box;
    swept.expand(Aabb{box.min + displacement, box.max + displacement});
    return swept.padded(margin);
}

// Built on the first query after an add (double-checked: queries after that read `built`
// and the tree without the lock).
struct StaticWorld::Tree {
    std::mutex mutex;
    std::atomic<bool> built{false};
    collision_detail::ColliderTree tree;
};

StaticWorld::StaticWorld() : tree_(std::make_unique<Tree>()) {}
StaticWorld::~StaticWorld() = default;
StaticWorld::StaticWorld(StaticWorld&&) noexcept = default;
StaticWorld& StaticWorld::operator=(StaticWorld&&) noexcept = default;

const StaticWorld::Tree& StaticWorld::tree() const {
    if (!tree_->built.load(std::memory_order_acquire)) {
        const std::lock_guard lock(tree_->mutex);
        if (!tree_->built.load(std::memory_order_relaxed)) {
            tree_->tree.build(bounds_);
            tree_->built.store(true, std::memory_order_release);
        }
    }
    return *tree_;
}

std::uint32_t StaticWorld::add(std::shared_ptr<const StaticCollider> collider) {
    if (!collider) throw Error("StaticWorld::add: the collider is null");
    if (colliders_.size() >= std::numeric_limits<std::uint32_t>::max())
        throw Error("StaticWorld::add: too many colliders");
    if (!tree_) tree_ = std::make_unique<Tree>();  // a moved-from world, used again
    bounds_.push_back(collider->bounds());
    colliders_.push_back(std::move(collider));
    tree_->built.store(false, std::memory_order_relaxed);
    return static_cast<std::uint32_t>(colliders_.size() - 1);
}

const StaticCollider& StaticWorld::collider(std::uint32_t id) const {
    if (id >= colliders_.size())
        throw Error("StaticWorld: no collider " + std::to_string(id) + " (the world has " +
                    std::to_string(colliders_.size()) + ")");
    return *colliders_[id];
}

void StaticWorld::query_aabb(const Aabb& box, std::vector<TriangleRef>& out) const {
    if (colliders_.empty()) return;
    // The colliders the tree passes are queried in batches, each collider's first lines
    // prefetched for the whole batch first: on a map of small tiles a car box meets two or
    // three, each a chain of cold loads (collider, root node, grids, slot blocks) that would
    // otherwise run one after another. A collider the tree passes though its exact box
    // misses `box` reports nothing (its triangles lie in that box): its query is the test.
    constexpr int kBatch = 16;
    std::uint32_t ids[kBatch];
    int count = 0;
    const auto query_batch = [&] {
        for (int i = 0; i < count; ++i) colliders_[ids[i]]->prefetch_box_query();
        for (int i = 0; i < count; ++i) colliders_[ids[i]]->query_aabb_refs(box, ids[i], out);
        count = 0;
    };
    tree().tree.visit_overlapping(box, [&](std::uint32_t id) {
        if (count == kBatch) query_batch();
        ids[count++] = id;
    });
    query_batch();
}

void StaticWorld::colliders_overlapping(const Aabb& box, std::vector<std::uint32_t>& out) const {
    if (colliders_.empty()) return;
    tree().tree.visit_overlapping(box, [&](std::uint32_t id) {
        if (bounds_[id].overlaps(box)) out.push_back(id);
    });
}

std::optional<WorldRayHit> StaticWorld::raycast(const glm::dvec3& origin,
                                                const glm::dvec3& unit_dir,
                                                double max_distance) const {
    const collision_detail::RayQuery ray =
        collision_detail::make_ray_query(origin, unit_dir, max_distance);
    std::optional<WorldRayHit> best;
    if (colliders_.empty()) return best;
    double limit = ray.max_distance;
    // Colliders come in id order, each box tested against the best distance so far (a
    // node's box holds its colliders', and the span test is monotone in the box, so a node
    // skipped at that distance holds no collider the loop over all would query).
    const auto reached = [&](const Aabb& box) {
        double t_near, t_far;
        return collision_detail::ray_box_span(ray, box.min, box.max, limit, t_near, t_far);
    };
    tree().tree.visit_nodes(reached, bounds_, [&](std::uint32_t id) {
        // Searching up to the best distance so far; only a strictly nearer hit replaces it.
        const std::optional<RayHit> hit = colliders_[id]->raycast(origin, unit_dir, limit);
        if (hit && (!best || hit->distance < limit)) {
            limit = hit->distance;
            best = WorldRayHit{id, *hit};
        }
    });
    return best;
}

}  // namespace trackphys
