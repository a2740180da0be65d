#include "trackphys/world/world_settings.hpp"

#include <cmath>
#include <sstream>

#include "trackphys/math/types.hpp"

namespace trackphys {

std::string WorldSettings::validate() const {
    std::ostringstream why;
    if (!(std::isfinite(dt_update) && dt_update > 0.0 && dt_update <= 1.0))
        why << "WorldSettings.dt_update must be in (0, 1] s, got " << dt_update;
    else if (steps < 1 || steps > 10000)
        why << "WorldSettings.steps must be in [1, 10000], got " << steps;
    else if (substeps < 1 || substeps > 10000)
        why << "WorldSettings.substeps must be in [1, 10000], got " << substeps;
    else if (!is_finite(gravity))
        why << "WorldSettings.gravity is not finite";
    else if (!(std::isfinite(broad_phase_margin) && broad_phase_margin >= 0.0))
        why << "WorldSettings.broad_phase_margin must be finite and >= 0, got "
            << broad_phase_margin;
    else if (mid_phase_look_ahead < 1)
        why << "WorldSettings.mid_phase_look_ahead must be >= 1, got " << mid_phase_look_ahead;
    else if (!(std::isfinite(mid_phase_slack) && mid_phase_slack >= 0.0))
        why << "WorldSettings.mid_phase_slack must be finite and >= 0, got " << mid_phase_slack;
    return why.str();
}

}  // namespace trackphys
