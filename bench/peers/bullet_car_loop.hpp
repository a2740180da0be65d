#pragma once

// The whole update with Bullet doing collision work (issue 7): the same trackphys Car and the
// same loop as World::update (steps x sub-steps, each ellipsoid's deepest contact fed to
// Car::advance), with Bullet's btGjkEpaSolver2 and the exact ellipsoid support shape
// (peers/bullet_contact.hpp) as the narrow phase, in two ways:
//
// - BulletCarLoop, "GJK/EPA per broad-phase candidate": the collision as Bullet's own
//   convex-vs-mesh algorithm (btConvexConcaveCollisionAlgorithm) does it: each sub-step,
//   each ellipsoid's box queried in the mesh's btBvhTriangleMeshShape (quantized BVH), and
//   GJK/EPA on every triangle it reports.
// - BulletNarrowPhaseLoop, "GJK/EPA per mid-phase candidate": our BVH and mid phase exactly
//   as World runs them (update box, look-ahead lists per ellipsoid), and GJK/EPA on every
//   triangle a list hands over in place of our cull and exact contact: the narrow phases
//   alone compared.
//
// Why separate loops and not a World setting: World's loop is private and built around our
// mid phase, cull and contact; keeping Bullet out of the library means repeating only the
// loop's structure here, through the public API (Car::world_ellipsoid and advance, MidPhase,
// LookAheadList), so the runs differ in the collision work alone.

#include <cstddef>
#include <memory>
#include <vector>

#include "peers/mesh_peer_harness.hpp"
#include "trackphys/collision/look_ahead_list.hpp"
#include "trackphys/collision/mid_phase.hpp"
#include "trackphys/collision/static_world.hpp"
#include "trackphys/dynamics/car.hpp"
#include "trackphys/world/world_settings.hpp"

namespace trackphys::peers {

/// GJK/EPA calls and Bullet's unanswered ones.
struct GjkEpaCounts {
    std::size_t pair_tests = 0, failures = 0;
};

class BulletCarLoop {
  public:
    /// Builds Bullet's BVH over `mesh` (one shape for the whole track).
    BulletCarLoop(const TriangleMesh& mesh, const WorldSettings& settings);

    /// One update of settings.dt_update for `car`.
    void update(Car& car);

    /// Since construction.
    const GjkEpaCounts& counts() const { return counts_; }
    double build_ms() const { return mesh_.build_ms; }

  private:
    BulletMesh mesh_;
    WorldSettings settings_;
    std::vector<Contact> deepest_;
    GjkEpaCounts counts_;
};

class BulletNarrowPhaseLoop {
  public:
    /// Our mid phase over `statics` in settings.mid_phase mode (with `trees` when that is
    /// precomputed_tree, e.g. a World's plane_trees()).
    BulletNarrowPhaseLoop(std::shared_ptr<const StaticWorld> statics, const WorldSettings& settings,
                          ColliderPlaneTrees trees);

    /// One update of settings.dt_update for `car`.
    void update(Car& car);

    /// Since construction.
    const GjkEpaCounts& counts() const { return counts_; }

  private:
    void begin_update(const Aabb& box);
    void list_step_candidates(const Car& car, int steps_left);

    std::shared_ptr<const StaticWorld> statics_;
    WorldSettings settings_;
    MidPhase mid_;
    Aabb update_box_;
    std::vector<LookAheadList> listed_;
    std::vector<Contact> deepest_;
    GjkEpaCounts counts_;
};

}  // namespace trackphys::peers
