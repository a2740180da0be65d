// Bullet's GJK/EPA (btGjkEpaSolver2) against ours on the same ellipsoid-triangle cases.
//
// Built twice from this file: bench_peers_contact_bullet_float (libBulletCollision, btScalar
// = float) and bench_peers_contact_bullet_double (-DBT_USE_DOUBLE_PRECISION with the
// *-float64 libraries). The two builds share symbol names, hence two programs.
//
// Bullet gets the exact ellipsoid: a convex shape whose support map is the ellipsoid's own,
// s(u) = D^2 u / ||D u|| in the ellipsoid frame (D = diag(radii)), margin 0 - not a hull,
// not btMultiSphereShape - against a btTriangleShape with margin 0, so GJK/EPA's answer can
// only be off by its own iteration and tolerance. A query is what btGjkEpaSolver2::
// SignedDistance does: GJK distance; when GJK finds the shapes overlapping, EPA
// penetration. Shapes are built per query from the case (a few ns).
//
//   build/release/bench/bench_peers_contact_bullet_float [--quick] [--json FILE]

#include <BulletCollision/CollisionShapes/btConvexInternalShape.h>
#include <BulletCollision/CollisionShapes/btTriangleShape.h>
#include <BulletCollision/NarrowPhaseCollision/btGjkEpa2.h>

#include <cmath>

#include "peers/contact_peer_harness.hpp"

namespace {

using trackphys::peers::PeerCase;
using trackphys::peers::PeerDepth;

/// A solid ellipsoid with semi-axes `radii` along its local axes, for Bullet's convex
/// algorithms: the exact support point in every direction.
ATTRIBUTE_ALIGNED16(class) EllipsoidShape : public btConvexInternalShape {
public:
    BT_DECLARE_ALIGNED_ALLOCATOR();

    explicit EllipsoidShape(const btVector3& radii) {
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

    void batchedUnitVectorGetSupportingVertexWithoutMargin(const btVector3* vectors,
                                                           btVector3* out,
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
    void calculateLocalInertia(btScalar mass, btVector3& inertia) const override {
        const btVector3 d2 = m_implicitShapeDimensions * m_implicitShapeDimensions;
        inertia = btVector3(d2.y() + d2.z(), d2.x() + d2.z(), d2.x() + d2.y()) * (mass / 5);
    }

    const char* getName() const override { return "Ellipsoid"; }
};

btVector3 bt(const glm::dvec3& v) {
    return {btScalar(v.x), btScalar(v.y), btScalar(v.z)};
}

/// GJK, then EPA when GJK says overlapping; depth = -signed distance.
PeerDepth bullet_gjk_epa(const PeerCase& c) {
    const trackphys::Ellipsoid& e = c.ellipsoid;
    const glm::dquat& q = e.orientation();
    const EllipsoidShape ellipsoid(bt(e.semi_axes()));
    const btTransform ellipsoid_pose(
        btQuaternion(btScalar(q.x), btScalar(q.y), btScalar(q.z), btScalar(q.w)),
        bt(e.center()));
    btTriangleShape triangle(bt(c.triangle[0]), bt(c.triangle[1]), bt(c.triangle[2]));
    triangle.setMargin(0);
    const btTransform identity = btTransform::getIdentity();
    const glm::dvec3 centroid = (c.triangle[0] + c.triangle[1] + c.triangle[2]) / 3.0;
    const btVector3 guess = bt(centroid - e.center());
    btGjkEpaSolver2::sResults results;
    if (btGjkEpaSolver2::Distance(&ellipsoid, ellipsoid_pose, &triangle, identity, guess,
                                  results))
        return {-double(results.distance), false};
    if (btGjkEpaSolver2::Penetration(&ellipsoid, ellipsoid_pose, &triangle, identity, guess,
                                     results, /*usemargins=*/false))
        return {-double(results.distance), false};
    return {0.0, true};
}

}  // namespace

int main(int argc, char** argv) {
#ifdef BT_USE_DOUBLE_PRECISION
    const char* program = "bench_peers_contact_bullet_double";
    const char* method = "bullet_double_gjk_epa";
#else
    const char* program = "bench_peers_contact_bullet_float";
    const char* method = "bullet_float_gjk_epa";
#endif
    return trackphys::peers::run_contact_peers(
        argc, argv, program, {trackphys::peers::per_case(method, bullet_gjk_epa)});
}
