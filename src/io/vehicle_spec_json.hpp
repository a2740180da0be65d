#pragma once

// VehicleSpec <-> the "vehicle" object of a car spec file (io/car_spec_json.hpp).

#include "json_reader.hpp"
#include "trackphys/vehicle/vehicle_spec.hpp"

namespace trackphys::json_io {

/// Reads value's keys over vehicle: each key left out keeps vehicle's value.
void vehicle_from_json(const Json& value, const std::string& path, const std::string& source,
                       VehicleSpec& vehicle);

/// vehicle as a JSON object with every key but "model" (the car spec's own key).
Json vehicle_to_json(const VehicleSpec& vehicle);

}  // namespace trackphys::json_io
