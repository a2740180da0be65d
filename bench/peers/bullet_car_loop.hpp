#pragma once

// The whole update with Bullet doing the collision work (issue 7): the same trackphys Car and
// the same loop as World::update (steps x sub-steps, each ellipsoid's deepest contact fed to
// Car::advance), with the collision done the way Bullet's own convex-vs-mesh algorithm
// (btConvexConcaveCollisionAlgorithm) does it: each sub-step, each ellipsoid's box queried
// in the mesh's btBvhTriangleMeshShape (quantized BVH), and btGjkEpaSolver2 with the exact
// ellipsoid support shape (peers/bullet_contact.hpp) on every triangle it reports.
//
// Why a separate loop and not a World setting: World's loop is private and built around our
// mid phase, cull and contact; keeping Bullet out of the library means repeating only the
// loop's structure here, through Car's public API (world_ellipsoid, advance), so the two
// runs differ in the collision work alone.

#include <cstddef>
#include <vector>

#include "peers/mesh_peer_harness.hpp"
#include "trackphys/dynamics/car.hpp"
#include "trackphys/world/world_settings.hpp"

namespace trackphys::peers {

class BulletCarLoop {
public:
    /// Builds Bullet's BVH over `mesh` (one shape for the whole track).
    BulletCarLoop(const TriangleMesh& mesh, const WorldSettings& settings);

    /// One update of settings.dt_update for `car`.
    void update(Car& car);

    /// Ellipsoid-triangle GJK/EPA calls and Bullet's unanswered ones since construction.
    std::size_t pair_tests() const { return pair_tests_; }
    std::size_t failures() const { return failures_; }
    double build_ms() const { return mesh_.build_ms; }

private:
    BulletMesh mesh_;
    WorldSettings settings_;
    std::vector<Contact> deepest_;
    std::size_t pair_tests_ = 0, failures_ = 0;
};

}  // namespace trackphys::peers
