#pragma once

#include <cstddef>

#include "trackphys/collision/static_collider.hpp"
#include "trackphys/dynamics/car.hpp"
#include "trackphys/dynamics/car_spec.hpp"
#include "trackphys/export.hpp"
#include "trackphys/geometry/aabb.hpp"
#include "trackphys/geometry/contact.hpp"
#include "trackphys/geometry/ellipsoid.hpp"
#include "trackphys/geometry/triangle.hpp"
#include "trackphys/world/contact_events.hpp"

namespace trackphys {

/// What World::debug_draw reports. Cars, ellipsoids and contacts by default; the collision
/// pipeline's working memory (update boxes, listed and kept triangles) on request, since a
/// car near a wall lists hundreds of triangles per ellipsoid.
struct DebugDrawOptions {
    bool cars = true;               ///< DebugDraw::draw_car
    bool ellipsoids = true;         ///< DebugDraw::draw_ellipsoid
    bool contacts = true;           ///< DebugDraw::draw_contact
    bool car_contacts = true;       ///< DebugDraw::draw_car_contact
    bool update_boxes = false;      ///< DebugDraw::draw_update_box
    bool listed_triangles = false;  ///< DebugDraw::draw_listed_triangle
    bool kept_triangles = false;    ///< DebugDraw::draw_kept_triangle

    /// Everything World::debug_draw can report.
    static DebugDrawOptions all() {
        return {.cars = true,
                .ellipsoids = true,
                .contacts = true,
                .car_contacts = true,
                .update_boxes = true,
                .listed_triangles = true,
                .kept_triangles = true};
    }
};

/// One of a car's ellipsoids as the world places it.
struct DebugEllipsoid {
    std::size_t car;        ///< index in the World (World::car)
    std::size_t ellipsoid;  ///< index in the car's CarSpec::ellipsoids
    Ellipsoid shape;        ///< world centre, orientation and semi-axes: Car::world_ellipsoid
    EllipsoidRole role;     ///< body or wheel
    double suspension;      ///< Car::suspension (m of compression; 0 for the body)
};

/// One ellipsoid's deepest contact, as World::contacts reports it.
struct DebugContact {
    std::size_t car;
    std::size_t ellipsoid;
    Contact contact;  ///< world point and normal, depth > 0 (m)
};

/// A static triangle the collision pipeline handed to one ellipsoid.
struct DebugTriangle {
    std::size_t car;
    std::size_t ellipsoid;
    TriangleRef ref;    ///< collider id and mesh triangle index
    Triangle triangle;  ///< world vertices (m), as the collider stores them
};

/// What a World shows of its last update, for a game to draw in its own renderer (as Box2D's
/// b2DebugDraw, Jolt's DebugRenderer, Bullet's btIDebugDraw, but in trackphys's terms:
/// ellipsoids and contacts rather than lines). World::debug_draw calls these; each has an
/// empty default, so an implementation overrides only what it draws. Calls come car by car
/// (World::car order); within a car: draw_car, its ellipsoids, its contacts, its update box,
/// its listed triangles, its kept triangles, each in ellipsoid order (CarSpec order); then
/// the contacts between cars, by pair.
/// The recording writer (RecordingWriter::write_frame) is one implementation.
class TRACKPHYS_API DebugDraw {
  public:
    virtual ~DebugDraw() = default;

    /// Car `index` after the last update: its state (pose, velocities), inputs, suspension.
    virtual void draw_car(std::size_t index, const Car& car);
    /// Each ellipsoid of the car, placed by the car's current state.
    virtual void draw_ellipsoid(const DebugEllipsoid& ellipsoid);
    /// Each ellipsoid's deepest contact of the last sub-step, only where it overlaps
    /// (depth > 0): exactly the entries of World::contacts(car) with depth > 0. They were
    /// found before that sub-step's integration, so a contact point lags the drawn ellipsoid
    /// by one sub-step of motion (settings().substep_dt() times the car's speed).
    virtual void draw_contact(const DebugContact& contact);
    /// Each pair of cars touching at the last sub-step, by (car_a, car_b): exactly
    /// World::car_contacts(). Found before that sub-step's integration, as draw_contact's.
    virtual void draw_car_contact(const CarPairContact& contact);
    /// The box the car's broad phase covered in its last update (m, world): every triangle
    /// the update could touch meets it.
    virtual void draw_update_box(std::size_t car, const Aabb& box);
    /// Each triangle the mid phase listed for the ellipsoid for the last step: the triangles
    /// the last sub-step's cull tested.
    virtual void draw_listed_triangle(const DebugTriangle& triangle);
    /// Each listed triangle that passed the last sub-step's cull, with the cull's upper bound
    /// of its penetration depth (m): the exact test's candidates, the first one tested first.
    virtual void draw_kept_triangle(const DebugTriangle& triangle, double depth_bound);
};

}  // namespace trackphys
