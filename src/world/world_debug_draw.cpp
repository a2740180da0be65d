// World::debug_draw: the cars and the collision pipeline's working memory as the last update
// left them, read from each car's slot (CarSlot::DrawnLists for the triangles).

#include "trackphys/world/debug_draw.hpp"
#include "trackphys/world/world.hpp"
#include "world/car_slot.hpp"

namespace trackphys {

// The defaults draw nothing: an implementation overrides what it shows.
void DebugDraw::draw_car(std::size_t, const Car&) {}
void DebugDraw::draw_ellipsoid(const DebugEllipsoid&) {}
void DebugDraw::draw_contact(const DebugContact&) {}
void DebugDraw::draw_car_contact(const CarPairContact&) {}
void DebugDraw::draw_update_box(std::size_t, const Aabb&) {}
void DebugDraw::draw_listed_triangle(const DebugTriangle&) {}
void DebugDraw::draw_kept_triangle(const DebugTriangle&, double) {}

void World::debug_draw(DebugDraw& draw, const DebugDrawOptions& options) const {
    for (std::size_t k = 0; k < cars_.size(); ++k) {
        const CarSlot& slot = cars_[k];
        const Car& car = slot.car;
        const std::size_t ellipsoids = car.ellipsoid_count();
        if (options.cars) draw.draw_car(k, car);
        if (options.ellipsoids)
            for (std::size_t i = 0; i < ellipsoids; ++i)
                draw.draw_ellipsoid({k, i, car.world_ellipsoid(i), car.spec().ellipsoids[i].role,
                                     car.suspension(i)});
        if (options.contacts)
            for (std::size_t i = 0; i < ellipsoids; ++i)
                if (slot.deepest[i].depth > 0.0) draw.draw_contact({k, i, slot.deepest[i]});
        if (options.update_boxes && !slot.update_box.empty())
            draw.draw_update_box(k, slot.update_box);
        const auto triangle = [&](std::size_t i, TriangleRef ref) {
            return DebugTriangle{k, i, ref,
                                 statics_->collider(ref.collider).triangle(ref.triangle)};
        };
        const CarSlot::DrawnLists& drawn = slot.drawn;
        if (options.listed_triangles)
            for (std::size_t i = 0; i + 1 < drawn.listed_start.size(); ++i)
                for (std::uint32_t j = drawn.listed_start[i]; j < drawn.listed_start[i + 1]; ++j)
                    draw.draw_listed_triangle(triangle(i, drawn.listed[j]));
        if (options.kept_triangles)
            for (std::size_t i = 0; i + 1 < drawn.kept_start.size(); ++i)
                for (std::uint32_t j = drawn.kept_start[i]; j < drawn.kept_start[i + 1]; ++j)
                    draw.draw_kept_triangle(triangle(i, drawn.kept[j].ref),
                                            drawn.kept[j].depth_bound);
    }
    if (options.car_contacts)
        for (const CarPairContact& contact : car_contacts()) draw.draw_car_contact(contact);
}

}  // namespace trackphys
