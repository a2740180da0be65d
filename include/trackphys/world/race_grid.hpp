#pragma once

#include <cstddef>
#include <vector>

#include "trackphys/collision/static_world.hpp"
#include "trackphys/dynamics/car_spec.hpp"
#include "trackphys/dynamics/rigid_body.hpp"
#include "trackphys/export.hpp"
#include "trackphys/track/track.hpp"

namespace trackphys {

/// The shape of a starting grid.
struct RaceGridSettings {
    double column_gap = 5.0;      ///< m across the track between the two columns' centres
    double row_gap = 10.0;        ///< m along the track between rows of the same column
    double first_row_back = 5.0;  ///< m from the start line back to the pole position
};

/// A car at rest on the surface of `statics` (place_car_on_surface) at centreline sample
/// `sample`, `across` m left of the centreline (negative: right), facing along the track.
/// Throws trackphys::Error as place_car_on_surface does.
TRACKPHYS_API RigidBodyState place_car_on_track(const StaticWorld& statics, const CarSpec& car,
                                                const CenterlineSample& sample, double across);

/// Start states for `cars` cars on a grid behind the start line of `track`: two columns,
/// column_gap apart and centred on the centreline, car 0 on pole (left column), car 1 in
/// the right column half a row further back, and so on, each row_gap behind the car two
/// places ahead. Every car faces along the track at rest on the surface of `statics`
/// (place_car_on_surface), so that World::add_car accepts it. Throws trackphys::Error
/// when the grid is longer than the track, for gaps that are not finite and > 0 (or
/// first_row_back not >= 0), or as place_car_on_surface does.
TRACKPHYS_API std::vector<RigidBodyState> race_grid(const Track& track, const StaticWorld& statics,
                                                    const CarSpec& car, std::size_t cars,
                                                    const RaceGridSettings& settings = {});

}  // namespace trackphys
