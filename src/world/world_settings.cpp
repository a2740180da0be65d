#include "trackphys/world/world_settings.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <thread>

#include <glm/geometric.hpp>

#include "trackphys/error.hpp"
#include "trackphys/math/types.hpp"

namespace trackphys {

int WorldSettings::thread_count() const {
    if (threads > 0) return threads;
    return std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
}

std::string WorldSettings::validate() const {
    std::ostringstream why;
    if (!(std::isfinite(dt_update) && dt_update > 0.0 && dt_update <= 1.0))
        why << "WorldSettings.dt_update must be in (0, 1] s, got " << exact_text(dt_update);
    else if (steps < 1 || steps > 10000)
        why << "WorldSettings.steps must be in [1, 10000], got " << steps;
    else if (substeps < 1 || substeps > 10000)
        why << "WorldSettings.substeps must be in [1, 10000], got " << substeps;
    else if (!(is_finite(gravity) && glm::length(gravity) <= kMaxGravity))
        why << "WorldSettings.gravity must be finite and at most " << exact_text(kMaxGravity)
            << " m/s^2 in magnitude, got (" << exact_text(gravity.x) << ", "
            << exact_text(gravity.y) << ", " << exact_text(gravity.z) << ")";
    else if (!(std::isfinite(broad_phase_margin) && broad_phase_margin >= 0.0))
        why << "WorldSettings.broad_phase_margin must be finite and >= 0, got "
            << exact_text(broad_phase_margin);
    else if (mid_phase_look_ahead < 1)
        why << "WorldSettings.mid_phase_look_ahead must be >= 1, got " << mid_phase_look_ahead;
    else if (!(std::isfinite(mid_phase_slack) && mid_phase_slack >= 0.0))
        why << "WorldSettings.mid_phase_slack must be finite and >= 0, got "
            << exact_text(mid_phase_slack);
    else if (!(std::isfinite(max_car_speed) && max_car_speed > 0.0))
        why << "WorldSettings.max_car_speed must be finite and > 0, got "
            << exact_text(max_car_speed);
    else if (!(std::isfinite(max_car_angular_speed) && max_car_angular_speed > 0.0))
        why << "WorldSettings.max_car_angular_speed must be finite and > 0, got "
            << exact_text(max_car_angular_speed);
    else if (!(max_spawn_distance >= 0.0))
        why << "WorldSettings.max_spawn_distance must be >= 0 (infinity for no limit), got "
            << exact_text(max_spawn_distance);
    else if (const std::string bad = check_surface_table(surfaces, "WorldSettings.surfaces");
             !bad.empty())
        why << bad;
    else if (threads < 0 || threads > 256)
        why << "WorldSettings.threads must be in [0, 256] (0: the hardware's count), got "
            << threads;
    else if ((jobs.enqueue_task == nullptr) != (jobs.finish_task == nullptr))
        why << "WorldSettings.jobs needs both enqueue_task and finish_task, or neither";
    else if (jobs.plugged_in() && jobs.worker_count < 1)
        why << "WorldSettings.jobs.worker_count must be >= 1, got " << jobs.worker_count;
    return why.str();
}

}  // namespace trackphys
