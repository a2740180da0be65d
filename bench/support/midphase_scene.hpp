#pragma once

// The mid phase on the default track's tightest banked turn at 1000 km/h
// (tightest_turn_scene.hpp), shared by bench_midphase and trackphys-bench:
// the track's colliders and precomputed plane trees, each step's query per ellipsoid (10
// steps x 8 ellipsoids), and one update's mid-phase work in each variant (mode, query shape,
// look-ahead).

#include <algorithm>
#include <chrono>
#include <compare>
#include <cstddef>
#include <memory>
#include <vector>

#include "tightest_turn_scene.hpp"
#include "trackphys/collision/look_ahead_list.hpp"
#include "trackphys/collision/mid_phase.hpp"
#include "trackphys/collision/static_world.hpp"
#include "trackphys/detail/plane_tree_builder.hpp"
#include "trackphys/geometry/ellipsoid.hpp"
#include "trackphys/world/world_settings.hpp"

namespace trackphys::bench {

/// What each step queries with: the ellipsoid's swept bounding sphere or the swept
/// ellipsoid itself (as World does).
enum class Shape { sphere, ellipsoid };

/// How far a point of the car can move beyond the translation in one 1 ms step: the car
/// turns at v / R = 278 / 26 = 10.7 rad/s, 0.011 rad a step, times the 1.9 m floor pan.
constexpr double kRotationMargin = 0.02;

struct StepQuery {
    glm::dvec3 start, end;
    double radius;
    Ellipsoid ellipsoid;
};

/// The default track as colliders (one per chunk), their precomputed trees and the
/// tightest turn's step queries. Built once, on first use.
struct MidScene {
    StaticWorld world;
    ColliderPlaneTrees trees;         // cost_based (the precomputed default)
    std::uint32_t turn_collider = 0;  // the collider with most candidates
    std::vector<StepQuery> queries;   // 10 steps x 8 ellipsoids
    /// Each sub-step's ellipsoids (40 x 8): the cull's inputs, placed as World has them from
    /// integrating, so that the cull is timed without the scene's kinematics.
    std::vector<Ellipsoid> placed;
    double trees_build_ms = 0.0;
    std::size_t trees_bytes = 0;

    MidScene();
};

const MidScene& mid_scene();

std::unique_ptr<MidPhase> make_mid_phase(MidPhaseMode mode);

/// One way of running an update's mid phase: the mode, the query shape, and how many steps
/// an ellipsoid query covers (World's look-ahead; spheres are queried every step).
struct MidVariant {
    MidPhaseMode mode;
    Shape shape;
    int look_ahead;
    const char* name;
    const char* note;
};

/// The variants compared, the write-up's loop (the reference) first.
const std::vector<MidVariant>& mid_variants();
inline constexpr std::size_t kWriteupVariant = 0;
inline constexpr std::size_t kDefaultVariant = 5;

/// What run_update fills: the step's list of each ellipsoid.
struct UpdateLists {
    std::vector<MidPhaseCandidate> spheres;  ///< a sphere query's list, this step
    std::vector<LookAheadList> ellipsoids;   ///< per ellipsoid, as World keeps them
};

/// The test each sub-step runs over the step's list, the loop's next stage.
enum class SubstepCull {
    none,
    bounding_sphere,  ///< the write-up's: the step's query sphere against the triangle
    world_extent,     ///< World's test, ellipsoid_depth_bound > 0 (scalar here; World runs it
                      ///< in SIMD lanes, the same bounds), dearer and tighter
};

/// One update's mid-phase work as World does it: begin_update, then per step each
/// ellipsoid's list: its swept bounding sphere queried for the step, or its swept ellipsoid
/// through a LookAheadList that looks variant.look_ahead steps ahead (within the update, and
/// within the update box) and is reused while the step stays inside. With a cull, also each
/// sub-step's cull over the step's list, so the time shows what the lists cost downstream;
/// the triangles it keeps are counted in `kept`. Returns the list lengths summed over the
/// steps.
std::size_t run_update(MidPhase& mid, const MidVariant& variant, SubstepCull cull,
                       UpdateLists& lists, std::size_t& kept);

/// A (sub-step, ellipsoid, triangle) entry of one update's lists.
struct ListEntry {
    int substep;
    std::size_t ellipsoid;
    TriangleRef ref;
    auto operator<=>(const ListEntry&) const = default;
};

/// The entries of one update's lists, as run_update builds them, that truly touch
/// (ellipsoid_triangle_contact deeper than 0), sorted and without repeats: lists that lost a
/// touching triangle miss an entry that the whole broad-phase list ("none") holds.
std::vector<ListEntry> touching_in_lists(MidPhase& mid, const MidVariant& variant,
                                         UpdateLists& lists);

/// The average list length: each step's list is tested in each of its 4 sub-steps.
double tested_per_ellipsoid_substep(std::size_t total_per_update);

}  // namespace trackphys::bench
