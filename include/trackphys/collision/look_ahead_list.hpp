#pragma once

#include <algorithm>
#include <cstddef>
#include <optional>
#include <vector>

#include <glm/vec3.hpp>

#include "trackphys/collision/mid_phase.hpp"
#include "trackphys/collision/swept_ellipsoid.hpp"
#include "trackphys/export.hpp"
#include "trackphys/math/types.hpp"

namespace trackphys {

/// The shape a mid-phase query covers when it looks `steps` steps ahead (>= 1) instead of
/// one: `step` (an ellipsoid swept at `velocity`, m/s, over one step of `step_dt` seconds)
/// swept `steps` steps along the same velocity, its margin grown by `slack` (m) when
/// steps > 1: the room a later step's small deviations from the straight path (a turn, a
/// bump) spend before a new query.
TRACKPHYS_API SweptEllipsoid look_ahead(const SweptEllipsoid& step, const glm::dvec3& velocity,
                                        double step_dt, int steps, double slack);

/// One ellipsoid's mid-phase candidates over the steps of an update, queried for a shape
/// that looks ahead (look_ahead) and reused by the following steps while their own swept
/// ellipsoid stays inside that shape. A query costs far more than culling a few more
/// triangles a sub-step, so World lists each ellipsoid's triangles for several steps at
/// once (WorldSettings::mid_phase_look_ahead):
///
///     if (!list.covers(step_shape))
///         list.refill(mid, look_ahead(step_shape, ..., list.steps_ahead(n, steps_left), ...));
///     for each sub-step: cull and test list.candidates()
///
/// Reuse never loses a triangle: a list holds every triangle of any shape its own contains().
class TRACKPHYS_API LookAheadList {
  public:
    /// True when the list holds every triangle `step` can touch.
    bool covers(const SweptEllipsoid& step) const { return shape_ && shape_->contains(step); }
    /// Replaces the list by mid's candidates for `shape`.
    void refill(MidPhase& mid, const SweptEllipsoid& shape);
    /// Forgets the list (its candidates come from a MidPhase update that has ended); the
    /// next steps_ahead still knows whether it was empty.
    void forget() { shape_.reset(); }
    /// Forgets the list and takes `was_empty` as whether the last one was empty: a list that
    /// serves one ellipsoid after another (a worker's, in World) carries each one's memory
    /// over from its own last list (was_empty()).
    void start_over(bool was_empty) {
        shape_.reset();
        candidates_.clear();
        was_empty_ = was_empty;
    }
    /// Whether the last list refilled was empty (true before the first).
    bool was_empty() const { return was_empty_; }
    /// How many steps the next query should cover: `look_ahead` (1: each step its own
    /// query, the write-up's loop), or when looking ahead at all and the last list was
    /// empty (a body ellipsoid riding above the road), every step left: an empty list costs
    /// the cull nothing however far it looks, so one query can serve the whole update.
    int steps_ahead(int look_ahead, int steps_left) const {
        if (look_ahead > 1 && was_empty_) return steps_left;
        return std::min(look_ahead, steps_left);
    }

    const std::vector<MidPhaseCandidate>& candidates() const { return candidates_; }
    /// Room for `candidates` before a refill allocates, and that room.
    void reserve(std::size_t candidates) { candidates_.reserve(candidates); }
    std::size_t capacity() const { return candidates_.capacity(); }

  private:
    std::vector<MidPhaseCandidate> candidates_;
    std::optional<SweptEllipsoid> shape_;
    bool was_empty_ = true;
};

}  // namespace trackphys
