#pragma once

/// The whole public API of trackphys in one include.

#include "trackphys/assert.hpp"
#include "trackphys/error.hpp"
#include "trackphys/export.hpp"
#include "trackphys/math/types.hpp"

#include "trackphys/geometry/aabb.hpp"
#include "trackphys/geometry/ellipsoid.hpp"
#include "trackphys/geometry/normalized_triangle.hpp"
#include "trackphys/geometry/sphere_cull_variants.hpp"
#include "trackphys/geometry/triangle.hpp"
#include "trackphys/geometry/triangle_mesh.hpp"
#include "trackphys/geometry/contact.hpp"
#include "trackphys/geometry/point_ellipse.hpp"
#include "trackphys/geometry/point_ellipsoid.hpp"
