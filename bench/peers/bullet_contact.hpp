#pragma once

// Bullet's GJK/EPA (btGjkEpaSolver2) on an ellipsoid and a triangle, with the exact
// ellipsoid (header-only; shared by bench_peers_contact_bullet_*, the Bullet whole-update
// loops and trackphys-bench). Compiles with either btScalar (float, or double with
// BT_USE_DOUBLE_PRECISION).
//
// Bullet gets the exact ellipsoid: a convex shape whose support map is the ellipsoid's own,
// s(u) = D^2 u / ||D u|| in the ellipsoid frame (D = diag(radii)), margin 0 - not a hull,
// not btMultiSphereShape - against a btTriangleShape with margin 0, so GJK/EPA's answer can
// only be off by its own iteration and tolerance. A query is what btGjkEpaSolver2::
// SignedDistance does: GJK distance; when GJK finds the shapes overlapping, EPA
// penetration. Shapes are built per query (a few ns).

#include <BulletCollision/CollisionShapes/btConvexInternalShape.h>
#include <BulletCollision/CollisionShapes/btTriangleShape.h>
#include <BulletCollision/NarrowPhaseCollision/btGjkEpa2.h>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "peers/contact_peer_harness.hpp"
#include "trackphys/geometry/contact.hpp"
#include "trackphys/geometry/ellipsoid.hpp"
#include "trackphys/geometry/triangle.hpp"

namespace trackphys::peers {

/// A solid ellipsoid with semi-axes `radii` along its local axes, for Bullet's convex
/// algorithms: the exact support point in every direction.
ATTRIBUTE_ALIGNED16(class) BulletEllipsoidShape : public btConvexInternalShape {
  public:
    BT_DECLARE_ALIGNED_ALLOCATOR();

    explicit BulletEllipsoidShape(const btVector3& radii) {
        // Not a known type: Bullet's non-virtual support dispatch falls back to the
        // virtual functions below.
        m_shapeType = CUSTOM_CONVEX_SHAPE_TYPE;
        m_implicitShapeDimensions = radii;
        setMargin(0);
    }

    /// The point of the ellipsoid farthest along u: x = D^2 u / ||D u||.
    btVector3 localGetSupportingVertexWithoutMargin(const btVector3& u) const override {
        const btVector3 du = m_implicitShapeDimensions * u;
        const btScalar length = du.length();
        if (!(length > btScalar(0))) return btVector3(m_implicitShapeDimensions.x(), 0, 0);
        return m_implicitShapeDimensions * du / length;
    }

    void batchedUnitVectorGetSupportingVertexWithoutMargin(const btVector3* vectors, btVector3* out,
                                                           int count) const override {
        for (int i = 0; i < count; ++i) out[i] = localGetSupportingVertexWithoutMargin(vectors[i]);
    }

    /// The tight world box: half extent along world axis i is ||row i of (R D)||.
    void getAabb(const btTransform& t, btVector3& min, btVector3& max) const override {
        const btMatrix3x3& r = t.getBasis();
        const btVector3& d = m_implicitShapeDimensions;
        btVector3 half;
        for (int i = 0; i < 3; ++i) half[i] = (r[i] * d).length();
        min = t.getOrigin() - half;
        max = t.getOrigin() + half;
    }

    /// Solid ellipsoid: I_x = m (b^2 + c^2) / 5, and so on.
    void calculateLocalInertia(btScalar mass, btVector3 & inertia) const override {
        const btVector3 d2 = m_implicitShapeDimensions * m_implicitShapeDimensions;
        inertia = btVector3(d2.y() + d2.z(), d2.x() + d2.z(), d2.x() + d2.y()) * (mass / 5);
    }

    const char* getName() const override { return "Ellipsoid"; }
};

inline btVector3 to_bullet(const glm::dvec3& v) {
    return {btScalar(v.x), btScalar(v.y), btScalar(v.z)};
}
inline glm::dvec3 from_bullet(const btVector3& v) {
    return {double(v.x()), double(v.y()), double(v.z())};
}

/// Bullet's answer for one pair, as ours: `contact` in trackphys::Contact's convention
/// (depth > 0 overlapping, normal pushing the ellipsoid out, point midway between the
/// witnesses); `failed` when neither GJK nor EPA answered (then depth = 0).
struct BulletContact {
    Contact contact;
    bool failed;
};

/// GJK, then EPA when GJK says overlapping; depth = -signed distance.
inline BulletContact bullet_gjk_epa(const Ellipsoid& e, const Triangle& t) {
    const glm::dquat& q = e.orientation();
    const BulletEllipsoidShape ellipsoid(to_bullet(e.semi_axes()));
    const btTransform ellipsoid_pose(
        btQuaternion(btScalar(q.x), btScalar(q.y), btScalar(q.z), btScalar(q.w)),
        to_bullet(e.center()));
    btTriangleShape triangle(to_bullet(t[0]), to_bullet(t[1]), to_bullet(t[2]));
    triangle.setMargin(0);
    const btTransform identity = btTransform::getIdentity();
    // GJK takes its first support point of ellipsoid - triangle at -guess in the ellipsoid's
    // frame: the best a cold call has is the line from the triangle's centroid to the centre.
    const glm::dvec3 centroid = (t[0] + t[1] + t[2]) / 3.0;
    const btVector3 guess =
        ellipsoid_pose.getBasis().transpose() * to_bullet(e.center() - centroid);
    btGjkEpaSolver2::sResults results;
    const bool answered =
        btGjkEpaSolver2::Distance(&ellipsoid, ellipsoid_pose, &triangle, identity, guess,
                                  results) ||
        btGjkEpaSolver2::Penetration(&ellipsoid, ellipsoid_pose, &triangle, identity, guess,
                                     results, /*usemargins=*/false);
    if (!answered) return {{0.0, {0.0, 1.0, 0.0}, e.center()}, true};
    const glm::dvec3 on_ellipsoid = from_bullet(results.witnesses[0]);
    const glm::dvec3 on_triangle = from_bullet(results.witnesses[1]);
    // Bullet's normal sign differs between its distance and penetration answers: orient it
    // from the triangle towards the ellipsoid's centre, the side a car is pushed back to.
    glm::dvec3 normal = from_bullet(results.normal);
    if (glm::dot(normal, e.center() - on_triangle) < 0.0) normal = -normal;
    return {{-double(results.distance), normal, 0.5 * (on_ellipsoid + on_triangle)}, false};
}

/// The harness's peer method (the depth only), named e.g. "bullet_float_gjk_epa".
inline Peer bullet_contact_peer(std::string name) {
    return per_case(std::move(name), [](const PeerCase& c) {
        const BulletContact r = bullet_gjk_epa(c.ellipsoid, c.triangle);
        return PeerDepth{r.contact.depth, r.failed};
    });
}

/// "float" or "double": the btScalar this translation unit was built with.
inline const char* bullet_precision() {
#ifdef BT_USE_DOUBLE_PRECISION
    return "double";
#else
    return "float";
#endif
}

}  // namespace trackphys::peers
