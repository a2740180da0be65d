#include "peers/bullet_car_loop.hpp"

#include <limits>

namespace trackphys::peers {
namespace {

/// Keeps the deepest Bullet contact of one ellipsoid over the triangles the BVH reports.
struct DeepestContact : btTriangleCallback {
    const Ellipsoid* ellipsoid = nullptr;
    Contact deepest{};
    std::size_t tests = 0, failures = 0;

    void processTriangle(btVector3* triangle, int /*part*/, int /*index*/) override {
        const BulletContact r = bullet_gjk_epa(
            *ellipsoid, Triangle(from_bullet(triangle[0]), from_bullet(triangle[1]),
                                 from_bullet(triangle[2])));
        ++tests;
        failures += r.failed;
        if (!r.failed && r.contact.depth > deepest.depth) deepest = r.contact;
    }
};

}  // namespace

BulletCarLoop::BulletCarLoop(const TriangleMesh& mesh, const WorldSettings& settings)
    : mesh_(mesh), settings_(settings) {}

void BulletCarLoop::update(Car& car) {
    deepest_.resize(car.ellipsoid_count());
    DeepestContact callback;
    // World's steps only refresh its mid-phase lists; Bullet queries its BVH every sub-step,
    // so the steps x sub-steps are one run of sub-steps here.
    for (int sub = 0; sub < settings_.steps * settings_.substeps; ++sub) {
        for (std::size_t i = 0; i < car.ellipsoid_count(); ++i) {
            const Ellipsoid ellipsoid = car.world_ellipsoid(i);
            const Aabb box = ellipsoid.bounds();
            callback.ellipsoid = &ellipsoid;
            callback.deepest.depth = -std::numeric_limits<double>::infinity();
            mesh_.shape->processAllTriangles(&callback, to_bullet(box.min), to_bullet(box.max));
            deepest_[i] = callback.deepest;
        }
        car.advance(deepest_, settings_.gravity, settings_.substep_dt());
    }
    pair_tests_ += callback.tests;
    failures_ += callback.failures;
}

}  // namespace trackphys::peers
