#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include <glm/vec3.hpp>

#include "trackphys/collision/static_collider.hpp"
#include "trackphys/export.hpp"
#include "trackphys/geometry/aabb.hpp"
#include "trackphys/math/types.hpp"

namespace trackphys {

/// The closest hit of a world ray cast: which collider, and the hit in it.
struct WorldRayHit {
    std::uint32_t collider;  ///< id given by StaticWorld::add
    RayHit hit;
};

/// The box a car sweeps in one update: its box at the start, its box moved by
/// `displacement` (velocity * dt, m), and `margin` (m, >= 0) on every side. Contacts that
/// can happen during the update involve only triangles overlapping this box.
TRACKPHYS_API Aabb swept_box(const Aabb& box, const glm::dvec3& displacement, double margin);

/// Every static collider of a world, and the world-level broad phase over them: a tree
/// over the collider boxes first (queries visit O(log n) of them), then each hit collider's
/// BVH (docs/design.md#broad-phase-the-bvh). Colliders are shared read-only (one track
/// chunk can sit in several worlds); queries are const and thread-safe. The tree is built
/// by the first query after an add() (O(n log n), under a lock, so concurrent first queries
/// build it once); after that queries are allocation-free once the caller's buffers have
/// grown. add() must not run concurrently with queries.
class TRACKPHYS_API StaticWorld {
  public:
    StaticWorld();
    ~StaticWorld();
    StaticWorld(StaticWorld&&) noexcept;
    StaticWorld& operator=(StaticWorld&&) noexcept;

    /// Adds a collider; returns its id (0, 1, 2... in order of addition). Throws
    /// trackphys::Error on a null pointer. Add every collider before making a World over
    /// this static world: a World in MidPhaseMode::precomputed_tree (the default) holds a
    /// plane tree per collider from its construction, and its add_car and update throw
    /// trackphys::Error once the counts differ.
    std::uint32_t add(std::shared_ptr<const StaticCollider> collider);

    /// Number of colliders (ids are 0 .. size() - 1).
    std::size_t size() const { return colliders_.size(); }
    /// Collider `id`; throws trackphys::Error for an id never returned by add().
    const StaticCollider& collider(std::uint32_t id) const;

    /// Appends (collider, triangle) for every kept triangle whose box overlaps `box`,
    /// colliders in id order (StaticCollider::query_aabb within each).
    void query_aabb(const Aabb& box, std::vector<TriangleRef>& out) const;

    /// Appends the id of every collider whose bounds overlap `box`, in id order.
    void colliders_overlapping(const Aabb& box, std::vector<std::uint32_t>& out) const;

    /// The closest hit over all colliders (StaticCollider::raycast); equal distances go to
    /// the lower collider id. Throws trackphys::Error on bad input as StaticCollider does.
    std::optional<WorldRayHit> raycast(const glm::dvec3& origin, const glm::dvec3& unit_dir,
                                       double max_distance) const;

  private:
    struct Tree;  // the tree over bounds_ and its lazy build (static_world.cpp)
    const Tree& tree() const;

    std::vector<std::shared_ptr<const StaticCollider>> colliders_;
    std::vector<Aabb> bounds_;  ///< colliders_[i]->bounds(), packed for the first test
    std::unique_ptr<Tree> tree_;
};

}  // namespace trackphys
