#pragma once

// Bullet's GJK/EPA (btGjkEpaSolver2) on an ellipsoid pair, for the ellipsoid-pair peer
// comparison: the exact ellipsoid support shape of bullet_contact.hpp for both ellipsoids,
// margin 0; GJK distance, and EPA penetration when GJK finds them overlapping. Float or
// double as the including program is built (BT_USE_DOUBLE_PRECISION).

#include <string>

#include "peers/bullet_contact.hpp"
#include "peers/ellipsoid_pair_peer_harness.hpp"

namespace trackphys::peers {

inline btTransform bullet_pose(const Ellipsoid& e) {
    const glm::dquat& q = e.orientation();
    return btTransform(btQuaternion(btScalar(q.x), btScalar(q.y), btScalar(q.z), btScalar(q.w)),
                       to_bullet(e.center()));
}

/// GJK distance, else EPA penetration, from `guess` (in a's local frame, where Bullet
/// forms the Minkowski difference).
inline PairPeerDepth bullet_pair_depth_from(const Ellipsoid& a, const Ellipsoid& b,
                                            const btTransform& pose_a, const btTransform& pose_b,
                                            const btVector3& guess) {
    const BulletEllipsoidShape shape_a(to_bullet(a.semi_axes()));
    const BulletEllipsoidShape shape_b(to_bullet(b.semi_axes()));
    btGjkEpaSolver2::sResults results;
    const bool answered =
        btGjkEpaSolver2::Distance(&shape_a, pose_a, &shape_b, pose_b, guess, results) ||
        btGjkEpaSolver2::Penetration(&shape_a, pose_a, &shape_b, pose_b, guess, results,
                                     /*usemargins=*/false);
    if (!answered) return {0.0, true};
    return {-double(results.distance), false};
}

/// Started from the centre line, the best guess a cold call has: GJK takes its first
/// support point of A - B at -guess, and for a separated pair the point of A - B nearest the
/// origin lies about along cA - cB, so the guess is cA - cB in a's local frame.
inline PairPeerDepth bullet_pair_depth(const Ellipsoid& a, const Ellipsoid& b) {
    const btTransform pose_a = bullet_pose(a), pose_b = bullet_pose(b);
    const btVector3 guess = pose_a.getBasis().transpose() * to_bullet(a.center() - b.center());
    return bullet_pair_depth_from(a, b, pose_a, pose_b, guess);
}

/// Started from an earlier contact's normal: GJK's first support point is taken in the
/// direction -guess of A - B, which for a separated pair is the minimiser n = -normal, so
/// the guess is the normal in a's local frame.
inline PairPeerDepth bullet_warm_pair_depth(const Ellipsoid& a, const Ellipsoid& b,
                                            const glm::dvec3& normal) {
    const btTransform pose_a = bullet_pose(a), pose_b = bullet_pose(b);
    const btVector3 guess = pose_a.getBasis().transpose() * to_bullet(normal);
    return bullet_pair_depth_from(a, b, pose_a, pose_b, guess);
}

/// The method, named after the precision it was built with ("bullet_float_gjk_epa").
inline PairPeer bullet_pair_peer() {
    return {std::string("bullet_") + bullet_precision() + "_gjk_epa", bullet_pair_depth};
}

/// The same, started from the earlier contact's normal.
inline WarmPairPeer bullet_warm_pair_peer() {
    return {std::string("bullet_") + bullet_precision() + "_gjk_epa", bullet_warm_pair_depth};
}

}  // namespace trackphys::peers
