#include "trackphys/world/race_grid.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include <glm/gtc/quaternion.hpp>
#include <glm/mat3x3.hpp>

#include "trackphys/error.hpp"
#include "trackphys/world/spawn.hpp"

namespace trackphys {
namespace {

// The centreline sample at or just before arc length s in [0, length).
const CenterlineSample& sample_at(const Track& track, double s) {
    const auto after = std::upper_bound(
        track.centerline.begin(), track.centerline.end(), s,
        [](double distance, const CenterlineSample& sample) { return distance < sample.distance; });
    return after == track.centerline.begin() ? track.centerline.front() : *(after - 1);
}

}  // namespace

RigidBodyState place_car_on_track(const StaticWorld& statics, const CarSpec& car,
                                  const CenterlineSample& sample, double across) {
    // Body axes +X left, +Y up, +Z forward onto the road frame there.
    const glm::dquat facing =
        glm::normalize(glm::quat_cast(glm::dmat3(sample.left, sample.up, sample.tangent)));
    const glm::dvec3 above =
        sample.position + sample.left * across + sample.up * (car.lowest_point_depth() + 0.5);
    return place_car_on_surface(statics, car, above, facing);
}

std::vector<RigidBodyState> race_grid(const Track& track, const StaticWorld& statics,
                                      const CarSpec& car, std::size_t cars,
                                      const RaceGridSettings& settings) {
    if (!(std::isfinite(settings.column_gap) && settings.column_gap > 0.0 &&
          std::isfinite(settings.row_gap) && settings.row_gap > 0.0 &&
          std::isfinite(settings.first_row_back) && settings.first_row_back >= 0.0))
        throw Error(
            "race_grid: column_gap and row_gap must be finite and > 0, first_row_back >= 0");
    if (track.centerline.empty()) throw Error("race_grid: the track has no centreline");
    const double grid_length =
        settings.first_row_back + 0.5 * settings.row_gap * static_cast<double>(cars);
    if (!(grid_length < track.length_m))
        throw Error("race_grid: " + std::to_string(cars) + " cars need " + exact_text(grid_length) +
                    " m of grid, the track is only " + exact_text(track.length_m) + " m long");

    std::vector<RigidBodyState> grid;
    grid.reserve(cars);
    for (std::size_t i = 0; i < cars; ++i) {
        const double back =
            settings.first_row_back + 0.5 * settings.row_gap * static_cast<double>(i);
        const double side = i % 2 == 0 ? 0.5 : -0.5;  // left column first
        grid.push_back(place_car_on_track(statics, car, sample_at(track, track.length_m - back),
                                          side * settings.column_gap));
    }
    return grid;
}

}  // namespace trackphys
