#pragma once

// The write-up's three sphere culls on the same inputs (shared by bench_sphere_cull and
// trackphys-bench): the broad-phase candidates of the default track's
// tightest banked turn against the bounding spheres of the default car's 8 ellipsoids over
// the 40 sub-steps of one update at 1000 km/h.
//   x-y-z order:   origin at the first vertex, tests in x, y, z order (its first version)
//   normal first:  the same layout, the plane distance first ("about half the cull time")
//   longest edge:  longest-edge origin, normal first, no min/max ("a little more")

#include <cstddef>
#include <utility>
#include <vector>

#include "geometry/sphere_cull_variants.hpp"
#include "tightest_turn_scene.hpp"
#include "trackphys/geometry/normalized_triangle.hpp"

namespace trackphys::bench {

enum class CullVariant { xyz_order, normal_first, longest_edge_normal_first };

/// The candidates as given and in both stored layouts, and the spheres.
struct CullScene {
    std::vector<BoundingSphere> spheres;
    std::vector<Triangle> triangles;
    std::vector<ArbitraryOriginTriangle> first_vertex_origin;
    std::vector<NormalizedTriangle> longest_edge_origin;

    explicit CullScene(const TightestTurnScene& turn)
        : CullScene(turn.bounding_spheres(), turn.candidates()) {}
    CullScene(std::vector<BoundingSphere> query_spheres, const std::vector<Triangle>& candidates)
        : spheres(std::move(query_spheres)),
          triangles(candidates),
          first_vertex_origin(candidates.begin(), candidates.end()),
          longest_edge_origin(candidates.begin(), candidates.end()) {}

    /// Sphere-triangle tests in one pass (every sphere against every candidate).
    std::size_t tests() const { return spheres.size() * longest_edge_origin.size(); }
};

/// One pass of `variant` over the scene: the number of (sphere, triangle) pairs kept.
std::size_t cull_pass(const CullScene& scene, CullVariant variant);

/// What a pass of `variant` must keep and did not: the (sphere, triangle) pairs within the
/// sphere's radius by the long-double reference distance that the variant rejects (0 for a
/// conservative cull), and how many pairs the reference places within reach.
struct CullCheck {
    std::size_t touching = 0, missed = 0;
};
CullCheck check_cull(const CullScene& scene, CullVariant variant);

}  // namespace trackphys::bench
