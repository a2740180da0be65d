#pragma once

#include <memory>
#include <optional>
#include <string_view>
#include <vector>

#include "trackphys/export.hpp"

namespace trackphys {

class PlaneTree;

/// How the triangles of one update are organised for the per-step, per-ellipsoid queries
/// (docs/design.md#mid-phase-plane-trees). Chosen by WorldSettings::mid_phase; MidPhase
/// (mid_phase.hpp) runs it.
enum class MidPhaseMode {
    /// No mid phase: every query returns the whole broad-phase candidate list.
    none,
    /// The write-up's WIP: a PCA plane tree (PlaneSplitRule::pca_median) built each update
    /// over the broad-phase candidates, queried per step.
    per_update_tree,
    /// Each collider's precomputed plane tree (make_collider_plane_tree), queried per step
    /// directly; the update only selects the colliders whose box meets the update box.
    precomputed_tree,
};

/// The default, the fastest mode in bench_midphase (docs/benchmarks.md): queried with swept
/// ellipsoids, the precomputed trees hand each ellipsoid a few triangles a sub-step where
/// the whole broad-phase list holds a hundred or more, and nothing is built per update.
inline constexpr MidPhaseMode kDefaultMidPhaseMode = MidPhaseMode::precomputed_tree;

/// "none", "per_update_tree" or "precomputed_tree".
TRACKPHYS_API std::string_view to_string(MidPhaseMode mode);
/// The mode with that name, or nullopt.
TRACKPHYS_API std::optional<MidPhaseMode> parse_mid_phase_mode(std::string_view name);

/// The precomputed trees of every collider of a world, index = collider id (what
/// MidPhase needs for MidPhaseMode::precomputed_tree). Shared read-only like the colliders.
using ColliderPlaneTrees = std::vector<std::shared_ptr<const PlaneTree>>;

}  // namespace trackphys
