#include "cull_scene.hpp"

namespace trackphys::bench {
namespace {

// Every variant's test is inline, so each pass is one loop with its test compiled into it.
template <class Stored, class Test>
std::size_t count_kept(const CullScene& scene, const std::vector<Stored>& stored, Test test) {
    std::size_t kept = 0;
    for (const BoundingSphere& s : scene.spheres)
        for (const Stored& t : stored) kept += test(t, s) ? 1 : 0;
    return kept;
}

}  // namespace

std::size_t cull_pass(const CullScene& scene, CullVariant variant) {
    switch (variant) {
        case CullVariant::xyz_order:
            return count_kept(scene, scene.first_vertex_origin,
                              [](const ArbitraryOriginTriangle& t, const BoundingSphere& s) {
                                  return t.may_touch_sphere_xyz(s.center, s.radius);
                              });
        case CullVariant::normal_first:
            return count_kept(scene, scene.first_vertex_origin,
                              [](const ArbitraryOriginTriangle& t, const BoundingSphere& s) {
                                  return t.may_touch_sphere_normal_first(s.center, s.radius);
                              });
        case CullVariant::longest_edge_normal_first:
            break;
    }
    return count_kept(scene, scene.longest_edge_origin,
                      [](const NormalizedTriangle& t, const BoundingSphere& s) {
                          return t.may_touch_sphere(s.center, s.radius);
                      });
}

}  // namespace trackphys::bench
