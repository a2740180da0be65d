#pragma once

#include <filesystem>
#include <fstream>
#include <string>

#include "trackphys/dynamics/car.hpp"

namespace trackphys::cli {

/// `trackphys drive --telemetry FILE.csv`: one row per update with named channels, units
/// in the names, the way sim-racing telemetry tools import CSV: time_s, speed_kmh, the
/// driver's inputs, and with a vehicle model engine_rpm, gear and per wheel (fl, fr, rl,
/// rr; wheel<n> beyond four) slip ratio, slip angle, load and spin.
class TelemetryCsv {
  public:
    /// Writes the header for car's channels to file. Throws trackphys::Error when the file
    /// cannot be written.
    TelemetryCsv(const std::filesystem::path& file, const Car& car);

    /// One row: the car after the update that ended at time seconds.
    void add(double time, const Car& car);
    /// Flushes; throws trackphys::Error when the file could not be written whole.
    void finish();

  private:
    std::filesystem::path file_;
    std::ofstream out_;
};

}  // namespace trackphys::cli
