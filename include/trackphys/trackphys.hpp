#pragma once

/// The whole public API of trackphys in one include.

#include "trackphys/assert.hpp"
#include "trackphys/build_target.hpp"
#include "trackphys/error.hpp"
#include "trackphys/export.hpp"

#include "trackphys/math/symmetric_eigen.hpp"
#include "trackphys/math/types.hpp"

#include "trackphys/geometry/aabb.hpp"
#include "trackphys/geometry/contact.hpp"
#include "trackphys/geometry/ellipsoid.hpp"
#include "trackphys/geometry/ellipsoid_cull.hpp"
#include "trackphys/geometry/ellipsoid_pair.hpp"
#include "trackphys/geometry/normalized_triangle.hpp"
#include "trackphys/geometry/point_ellipse.hpp"
#include "trackphys/geometry/point_ellipsoid.hpp"
#include "trackphys/geometry/triangle.hpp"
#include "trackphys/geometry/triangle_mesh.hpp"

#include "trackphys/collision/brute_force_collider.hpp"
#include "trackphys/collision/mid_phase.hpp"
#include "trackphys/collision/mid_phase_mode.hpp"
#include "trackphys/collision/plane_tree.hpp"
#include "trackphys/collision/static_collider.hpp"
#include "trackphys/collision/static_world.hpp"
#include "trackphys/collision/look_ahead_list.hpp"
#include "trackphys/collision/swept_ellipsoid.hpp"

#include "trackphys/dynamics/car.hpp"
#include "trackphys/dynamics/car_spec.hpp"
#include "trackphys/dynamics/contact_force.hpp"
#include "trackphys/dynamics/rigid_body.hpp"

#include "trackphys/world/autopilot.hpp"
#include "trackphys/world/spawn.hpp"
#include "trackphys/world/world.hpp"
#include "trackphys/world/world_settings.hpp"
#include "trackphys/world/world_snapshot.hpp"

#include "trackphys/profile/profile_statistics.hpp"
#include "trackphys/profile/trace_recorder.hpp"
#include "trackphys/profile/update_profile.hpp"

#include "trackphys/track/track.hpp"
#include "trackphys/track/track_params.hpp"
#include "trackphys/track/track_stats.hpp"

#include "trackphys/io/car_spec_json.hpp"
#include "trackphys/io/mesh_io.hpp"
#include "trackphys/io/recording.hpp"
#include "trackphys/io/scenario.hpp"
#include "trackphys/io/snapshot_file.hpp"
