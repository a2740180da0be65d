// Bullet's GJK/EPA (btGjkEpaSolver2) against ours on the same ellipsoid pairs.
//
// Built twice from this file, like bench_peers_contact_bullet_*: float (libBulletCollision)
// and double (-DBT_USE_DOUBLE_PRECISION with the *-float64 libraries). Bullet gets the
// exact ellipsoid support shape of peers/bullet_contact.hpp for both ellipsoids, margin 0:
// GJK distance, and EPA penetration when GJK finds them overlapping.
//
//   build/release/bench/peers/bench_peers_ellipsoid_pair_bullet_float [--quick]

#include "peers/bullet_contact.hpp"
#include "peers/ellipsoid_pair_peer_harness.hpp"

namespace {

using namespace trackphys;
using namespace trackphys::peers;

btTransform pose(const Ellipsoid& e) {
    const glm::dquat& q = e.orientation();
    return btTransform(btQuaternion(btScalar(q.x), btScalar(q.y), btScalar(q.z), btScalar(q.w)),
                       to_bullet(e.center()));
}

PairPeerDepth bullet_pair(const Ellipsoid& a, const Ellipsoid& b) {
    const BulletEllipsoidShape shape_a(to_bullet(a.semi_axes()));
    const BulletEllipsoidShape shape_b(to_bullet(b.semi_axes()));
    const btTransform pose_a = pose(a), pose_b = pose(b);
    const btVector3 guess = to_bullet(b.center() - a.center());
    btGjkEpaSolver2::sResults results;
    const bool answered =
        btGjkEpaSolver2::Distance(&shape_a, pose_a, &shape_b, pose_b, guess, results) ||
        btGjkEpaSolver2::Penetration(&shape_a, pose_a, &shape_b, pose_b, guess, results,
                                     /*usemargins=*/false);
    if (!answered) return {0.0, true};
    return {-double(results.distance), false};
}

}  // namespace

int main(int argc, char** argv) {
    const std::string program =
        std::string("bench_peers_ellipsoid_pair_bullet_") + bullet_precision();
    const std::string method = std::string("bullet_") + bullet_precision() + "_gjk_epa";
    return run_pair_peers(argc, argv, program.c_str(), {{method, bullet_pair}});
}
