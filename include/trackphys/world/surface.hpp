#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>

#include "trackphys/collision/static_collider.hpp"
#include "trackphys/export.hpp"
#include "trackphys/geometry/triangle_mesh.hpp"

namespace trackphys {

/// How one surface (an entry of WorldSettings::surfaces, indexed by SurfaceId) drives
/// compared with the dry road (docs/design.md#surfaces).
struct Surface {
    /// Friction relative to the dry road (in (0, max_surface_grip]; 1 the dry road, about
    /// 0.6 grass or gravel, 0.1 ice). It scales the friction of every contact on the
    /// surface: the arcade
    /// car's wheel grip and traction limit, a vehicle model's tyre peaks (times the wheel's
    /// Vehicle::set_road_grip), and any car's body friction.
    double grip = 1.0;
};

/// The most a surface grips, relative to the dry road: no road grips ten times a dry one,
/// and a friction much stiffer than that outruns the sub-step (a grip of 1000 throws the
/// car off the road in its first updates).
inline constexpr double max_surface_grip = 10.0;

/// Empty when `table` can be a surface table (WorldSettings::surfaces): at most max_surfaces
/// entries, each grip in (0, max_surface_grip]. Otherwise the first problem, the table
/// called `name` ("WorldSettings.surfaces[2].grip must be in (0, 10], got -1").
TRACKPHYS_API std::string check_surface_table(std::span<const Surface> table,
                                              std::string_view name);

/// What ellipsoid k of a car touched at the last sub-step of the last update
/// (World::contact_surface): the triangle of its deepest contact and that triangle's surface.
struct ContactSurface {
    TriangleRef triangle;  ///< collider id and mesh triangle index
    SurfaceId surface;     ///< TriangleMesh::surfaces of that triangle (0 when it had none)
};

}  // namespace trackphys
