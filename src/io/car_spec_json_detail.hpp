#pragma once

// CarSpec <-> JSON values, shared by car spec files and the car inside a scenario.

#include <span>
#include <string>

#include "json_reader.hpp"
#include "trackphys/dynamics/car_spec.hpp"

namespace trackphys::json_io {

/// The spec in value (an object at path of the document named source), validated; see
/// car_spec_json.hpp for the format and the errors.
CarSpec car_spec_from_json(const Json& value, const std::string& path, const std::string& source);

/// The ellipsoids as CarSpec's "ellipsoids" array (also the recording header's).
Json car_ellipsoids_to_json(std::span<const CarEllipsoid> ellipsoids);

/// spec as a JSON object with every key.
Json car_spec_to_json_value(const CarSpec& spec);

}  // namespace trackphys::json_io
