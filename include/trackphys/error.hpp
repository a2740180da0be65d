#pragma once

#include <stdexcept>
#include <string>

#include "trackphys/export.hpp"

namespace trackphys {

/// Every error trackphys reports on bad input: a mesh file it cannot read, an invalid
/// ellipsoid, an inconsistent configuration. The message names the thing and the reason.
class TRACKPHYS_API Error : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

}  // namespace trackphys
