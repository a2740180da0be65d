#include "cull_scene.hpp"

#include "support/closest_point_reference.hpp"

namespace trackphys::bench {
namespace {

// Calls f(stored, keeps) with the variant's stored triangles and its sphere test. Every
// variant's test is inline, so a pass is one loop with its test compiled into it.
template <class F>
auto with_variant(const CullScene& scene, CullVariant variant, F f) {
    switch (variant) {
        case CullVariant::xyz_order:
            return f(scene.first_vertex_origin,
                     [](const ArbitraryOriginTriangle& t, const BoundingSphere& s) {
                         return t.may_touch_sphere_xyz(s.center, s.radius);
                     });
        case CullVariant::normal_first:
            return f(scene.first_vertex_origin,
                     [](const ArbitraryOriginTriangle& t, const BoundingSphere& s) {
                         return t.may_touch_sphere_normal_first(s.center, s.radius);
                     });
        case CullVariant::longest_edge_normal_first:
            break;
    }
    return f(scene.longest_edge_origin, [](const NormalizedTriangle& t, const BoundingSphere& s) {
        return t.may_touch_sphere(s.center, s.radius);
    });
}

}  // namespace

std::size_t cull_pass(const CullScene& scene, CullVariant variant) {
    return with_variant(scene, variant, [&](const auto& stored, auto keeps) {
        std::size_t kept = 0;
        for (const BoundingSphere& s : scene.spheres)
            for (const auto& t : stored) kept += keeps(t, s) ? 1 : 0;
        return kept;
    });
}

CullCheck check_cull(const CullScene& scene, CullVariant variant) {
    return with_variant(scene, variant, [&](const auto& stored, auto keeps) {
        CullCheck check;
        for (const BoundingSphere& s : scene.spheres)
            for (std::size_t i = 0; i < stored.size(); ++i) {
                const Triangle& t = scene.triangles[i];
                if (test::point_triangle_distance(s.center, t[0], t[1], t[2]) > s.radius) continue;
                ++check.touching;
                if (!keeps(stored[i], s)) ++check.missed;
            }
        return check;
    });
}

}  // namespace trackphys::bench
