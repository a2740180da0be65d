#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include <glm/vec3.hpp>

#include "trackphys/collision/mid_phase_mode.hpp"
#include "trackphys/collision/plane_tree.hpp"
#include "trackphys/collision/plane_tree_frame_cache.hpp"
#include "trackphys/collision/static_collider.hpp"
#include "trackphys/collision/static_world.hpp"
#include "trackphys/detail/plane_tree_builder.hpp"
#include "trackphys/export.hpp"
#include "trackphys/geometry/aabb.hpp"
#include "trackphys/geometry/ellipsoid.hpp"
#include "trackphys/geometry/normalized_triangle.hpp"
#include "trackphys/math/types.hpp"

namespace trackphys {

/// One triangle a mid-phase query hands to the sub-step loop.
struct MidPhaseCandidate {
    TriangleRef ref;                     ///< 8 bytes: collider id and mesh triangle index
    const NormalizedTriangle* triangle;  ///< 8 bytes: for the cull and the exact contact
};
static_assert(sizeof(MidPhaseCandidate) == 16, "MidPhaseCandidate is 16 bytes");

/// Work counted since the last reset_counters(), for profiles and benchmarks.
struct MidPhaseCounters {
    std::size_t updates = 0;
    std::size_t broad_phase_candidates = 0;  ///< summed over updates (none, per_update_tree)
    std::size_t queries = 0;
    std::size_t candidates = 0;          ///< returned by queries, summed
    std::size_t planes_tested = 0;       ///< tree queries only
    std::size_t triangles_filtered = 0;  ///< tree queries only
};

/// Builds make_collider_plane_tree for every collider of `world` (result in id order) on up
/// to `threads` threads (0: std::thread::hardware_concurrency()), keeping the frames when
/// the world's fit in `frame_budget_bytes` (plane_tree_frames_within). With fewer colliders
/// than threads, each tree is built on the threads left over (one big collider on them
/// all). The trees do not depend on the thread count.
TRACKPHYS_API ColliderPlaneTrees make_collider_plane_trees(
    const StaticWorld& world, const PlaneTreeSettings& settings = PlaneTreeSettings::precomputed(),
    unsigned threads = 0, std::size_t frame_budget_bytes = kPlaneTreeFrameBudget);

/// The mid phase of one car: what a World calls once per update and then per step per
/// ellipsoid, whatever the mode. Holds per-update state and scratch (one per car, not
/// shared between threads); the StaticWorld and the trees are only read and must outlive it.
///
///     mid.begin_update(update_box);                     // once per update
///     for each step, for each ellipsoid:
///         list.clear();
///         mid.query_swept_ellipsoid(e, e_end, margin, list);   // or query_swept_sphere
///         for each sub-step: cull and test list[i].triangle
///
/// Every query returns a superset of the triangles its shape touches among those the
/// update box admits: the whole broad-phase list (none), or exactly the triangles the shape
/// touches (the tree modes, see PlaneTree for the filter). The shapes of an update must lie
/// inside its update box, as the broad phase already requires. Candidate pointers stay valid
/// until the next begin_update (none, per_update_tree), or, in precomputed_tree mode, until
/// a begin_update whose box does not hold the previous one (a World that widens an update's
/// box mid-step keeps culling with the lists it queried before). No allocation once the
/// buffers have grown.
class TRACKPHYS_API MidPhase {
  public:
    /// Throws trackphys::Error when mode is precomputed_tree and `trees` does not hold one
    /// non-null tree per collider of `world` (their count is checked again at each
    /// begin_update, since colliders can be added to the world later).
    MidPhase(MidPhaseMode mode, const StaticWorld& world, ColliderPlaneTrees trees = {});
    /// The same with trees shared with other MidPhases (a World's cars): one copy of the
    /// vector for all of them, which stays in cache where a copy per car would not.
    MidPhase(MidPhaseMode mode, const StaticWorld& world,
             std::shared_ptr<const ColliderPlaneTrees> trees);

    MidPhaseMode mode() const { return mode_; }

    /// Starts an update whose shapes all lie in `update_box` (the car's swept, padded box):
    /// gathers the broad-phase candidates (none, per_update_tree; the latter also builds its
    /// tree over them) or selects the colliders whose bounds meet the box and the node of
    /// each tree where the update's queries start (precomputed_tree).
    void begin_update(const Aabb& update_box);

    /// Appends the candidates for a sphere of `radius` (m) moving from start to end during
    /// a step (an ellipsoid's bounding sphere). Throws trackphys::Error on non-finite input
    /// or a negative radius.
    void query_swept_sphere(const glm::dvec3& start, const glm::dvec3& end, double radius,
                            std::vector<MidPhaseCandidate>& out);
    /// Appends the candidates for the ellipsoid moving to `end` during a step, grown by
    /// `margin` (m) for its rotation (PlaneTree::query_swept_ellipsoid). Tighter than the
    /// bounding sphere: a flat body ellipsoid above the road gets no road triangles at all.
    void query_swept_ellipsoid(const Ellipsoid& ellipsoid, const glm::dvec3& end, double margin,
                               std::vector<MidPhaseCandidate>& out);

    /// Broad-phase candidates of the current update (empty in precomputed_tree mode).
    std::size_t broad_phase_candidate_count() const { return refs_.size(); }
    const MidPhaseCounters& counters() const { return counters_; }
    void reset_counters() { counters_ = {}; }
    /// Bytes of per-update storage and scratch (not the shared trees).
    std::size_t bytes_used() const;

  private:
    template <class Query>
    void query(Query&& query_tree, std::vector<MidPhaseCandidate>& out);
    void check_tree_count() const;

    MidPhaseMode mode_;
    const StaticWorld* world_;
    std::shared_ptr<const ColliderPlaneTrees> trees_;  // never null
    // none / per_update_tree: the broad-phase candidates and their frames, same order.
    std::vector<TriangleRef> refs_;
    std::vector<NormalizedTriangle> triangles_;
    // per_update_tree: the tree over them (ids index refs_) and its builder.
    std::vector<std::uint32_t> ids_;
    PlaneTree update_tree_;
    PlaneTreeBuilder builder_;
    // precomputed_tree: the colliders this update can touch and where in each tree the
    // update's queries start (PlaneTree::entry_node of the update box).
    std::vector<std::uint32_t> active_colliders_;
    std::vector<std::uint32_t> entry_nodes_;
    std::vector<std::uint32_t> slots_;
    // precomputed_tree: the frames the trees' filters built (a collider's tree keeps none),
    // which candidates point at, since the update box frames_box_ (see begin_update).
    PlaneTreeFrameCache frames_;
    Aabb frames_box_;
    MidPhaseCounters counters_;
};

}  // namespace trackphys
