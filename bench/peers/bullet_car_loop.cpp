#include "peers/bullet_car_loop.hpp"

#include <limits>
#include <utility>

#include <glm/geometric.hpp>

#include "dynamics/car_access.hpp"
#include "world/update_box.hpp"

namespace trackphys::peers {
namespace {

/// Keeps the deepest Bullet contact of one ellipsoid over the triangles it is shown.
struct DeepestContact : btTriangleCallback {
    const Ellipsoid* ellipsoid = nullptr;
    Contact deepest{};
    GjkEpaCounts* counts = nullptr;

    void start(const Ellipsoid& e) {
        ellipsoid = &e;
        deepest.depth = -std::numeric_limits<double>::infinity();
    }
    void add(const Triangle& triangle) {
        const BulletContact r = bullet_gjk_epa(*ellipsoid, triangle);
        ++counts->pair_tests;
        counts->failures += r.failed;
        if (!r.failed && r.contact.depth > deepest.depth) deepest = r.contact;
    }
    void processTriangle(btVector3* triangle, int /*part*/, int /*index*/) override {
        add(Triangle(from_bullet(triangle[0]), from_bullet(triangle[1]), from_bullet(triangle[2])));
    }
};

}  // namespace

BulletCarLoop::BulletCarLoop(const TriangleMesh& mesh, const WorldSettings& settings)
    : mesh_(mesh), settings_(settings) {}

void BulletCarLoop::update(Car& car) {
    deepest_.resize(car.ellipsoid_count());
    DeepestContact callback;
    callback.counts = &counts_;
    // World's steps only refresh its mid-phase lists; Bullet queries its BVH every sub-step,
    // so the steps x sub-steps are one run of sub-steps here.
    for (int sub = 0; sub < settings_.steps * settings_.substeps; ++sub) {
        for (std::size_t i = 0; i < car.ellipsoid_count(); ++i) {
            const Ellipsoid ellipsoid = car.world_ellipsoid(i);
            const Aabb box = ellipsoid.bounds();
            callback.start(ellipsoid);
            mesh_.shape->processAllTriangles(&callback, to_bullet(box.min), to_bullet(box.max));
            deepest_[i] = callback.deepest;
        }
        detail::CarAccess::advance(car, deepest_, settings_.gravity, settings_.substep_dt());
    }
}

BulletNarrowPhaseLoop::BulletNarrowPhaseLoop(std::shared_ptr<const StaticWorld> statics,
                                             const WorldSettings& settings,
                                             ColliderPlaneTrees trees)
    : statics_(std::move(statics)),
      settings_(settings),
      mid_(settings.mid_phase, *statics_, std::move(trees)) {}

// The update box, the steps and the look-ahead lists as World::update_car and
// World::list_step_candidates make them (src/world/world.cpp).
void BulletNarrowPhaseLoop::update(Car& car) {
    listed_.resize(car.ellipsoid_count());
    deepest_.resize(car.ellipsoid_count());
    begin_update(detail::car_update_box(car, settings_));
    DeepestContact deepest;
    deepest.counts = &counts_;
    for (int step = 0; step < settings_.steps; ++step) {
        list_step_candidates(car, settings_.steps - step);
        for (int s = 0; s < settings_.substeps; ++s) {
            for (std::size_t i = 0; i < car.ellipsoid_count(); ++i) {
                const Ellipsoid ellipsoid = car.world_ellipsoid(i);
                deepest.start(ellipsoid);
                for (const MidPhaseCandidate& c : listed_[i].candidates())
                    deepest.add(statics_->collider(c.ref.collider).triangle(c.ref.triangle));
                deepest_[i] = deepest.deepest;
            }
            detail::CarAccess::advance(car, deepest_, settings_.gravity, settings_.substep_dt());
        }
    }
}

void BulletNarrowPhaseLoop::begin_update(const Aabb& box) {
    update_box_ = box;
    mid_.begin_update(box);
    for (LookAheadList& list : listed_) list.forget();
}

void BulletNarrowPhaseLoop::list_step_candidates(const Car& car, int steps_left) {
    const RigidBodyState& state = car.state();
    const double step_dt = settings_.dt_update / settings_.steps;
    const double spin = glm::length(state.angular_velocity);
    for (std::size_t i = 0; i < car.ellipsoid_count(); ++i) {
        const Ellipsoid ellipsoid = car.world_ellipsoid(i);
        const glm::dvec3 velocity = point_velocity(state, ellipsoid.center());
        const double margin = spin * ellipsoid.bounding_radius() * step_dt + 10.0 * step_dt;
        const SweptEllipsoid step_shape{ellipsoid, ellipsoid.center() + velocity * step_dt, margin};
        LookAheadList& listed = listed_[i];
        if (listed.covers(step_shape)) continue;
        SweptEllipsoid wanted =
            look_ahead(step_shape, velocity, step_dt,
                       listed.steps_ahead(settings_.mid_phase_look_ahead, steps_left),
                       settings_.mid_phase_slack);
        if (!update_box_.contains(wanted.bounds())) wanted = step_shape;
        if (!update_box_.contains(wanted.bounds())) {
            Aabb wider = update_box_;
            wider.expand(wanted.bounds().padded(settings_.broad_phase_margin));
            begin_update(wider);
        }
        listed.refill(mid_, wanted);
    }
}

}  // namespace trackphys::peers
