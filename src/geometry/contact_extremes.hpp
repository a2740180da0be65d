#pragma once

// The contact at extreme scales (internal): configurations whose lengths leave the fast
// path's window (contact.cpp) are solved here at unit scale, or with the ellipsoid as a
// point when it is below 2^-200 of the configuration.

#include <array>

#include <glm/vec3.hpp>

#include "trackphys/geometry/contact.hpp"
#include "trackphys/geometry/ellipsoid.hpp"

namespace trackphys::detail {

/// ellipsoid_triangle_contact for a finite triangle v (canonical vertex order) of any size.
Contact rescaled_contact(const Ellipsoid& ellipsoid, const std::array<glm::dvec3, 3>& v);

}  // namespace trackphys::detail
