#include "trackphys/collision/look_ahead_list.hpp"

namespace trackphys {

SweptEllipsoid look_ahead(const SweptEllipsoid& step, const glm::dvec3& velocity, double step_dt,
                          int steps, double slack) {
    if (steps <= 1) return step;
    return {step.ellipsoid, step.end + velocity * (step_dt * (steps - 1)), step.margin + slack};
}

void LookAheadList::refill(MidPhase& mid, const SweptEllipsoid& shape) {
    shape_ = shape;
    candidates_.clear();
    was_empty_ = true;  // as the list is, should the query throw (a non-finite shape)
    mid.query_swept_ellipsoid(shape.ellipsoid, shape.end, shape.margin, candidates_);
    was_empty_ = candidates_.empty();
}

}  // namespace trackphys
