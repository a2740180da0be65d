#pragma once

// The vehicle's part of fingerprint(CarSpec) (world/world_snapshot.hpp) and of
// World::state_hash.

#include <cstdint>

#include "core/fnv1a.hpp"
#include "trackphys/vehicle/vehicle.hpp"
#include "trackphys/vehicle/vehicle_spec.hpp"

namespace trackphys {

/// Adds every field of the vehicle's state to a world's state hash.
void add_to_hash(core::Fnv1a& hash, const VehicleState& state);

/// A hash of every field of the vehicle spec (bits of every double): equal for equal specs.
std::uint64_t fingerprint(const VehicleSpec& vehicle);

}  // namespace trackphys
