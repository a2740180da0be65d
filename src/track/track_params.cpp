#include "trackphys/track/track_params.hpp"

#include <cmath>
#include <numbers>
#include <sstream>
#include <string>

#include "track/track_shape.hpp"
#include "trackphys/error.hpp"

namespace trackphys {
namespace {

// Largest track the generator accepts, in triangles (estimated from the density before
// generating): ~1 GB of mesh, far beyond any game track.
constexpr double kTriangleBudget = 2e7;

[[noreturn]] void fail(const std::string& field, const std::string& rule, double value) {
    std::ostringstream message;
    message << "TrackParams." << field << " " << rule << ", got " << exact_text(value);
    throw Error(message.str());
}

// value must be finite and lo <= value <= hi (lo excluded when open_low).
void check_range(const char* field, double value, double lo, double hi, const char* unit,
                 bool open_low = false) {
    const bool low_ok = open_low ? value > lo : value >= lo;
    if (!std::isfinite(value) || !low_ok || !(value <= hi)) {
        std::ostringstream rule;
        rule << "must be finite and in " << (open_low ? "(" : "[") << exact_text(lo) << ", "
             << exact_text(hi) << "] " << unit;
        fail(field, rule.str(), value);
    }
}

}  // namespace

void validate_track_params(const TrackParams& p) {
    check_range("length_m", p.length_m, 200.0, 1e6, "m");
    check_range("width_m", p.width_m, 0.0, 100.0, "m", true);
    check_range("max_bank_deg", p.max_bank_deg, 0.0, 60.0, "degrees");
    check_range("full_bank_radius_m", p.full_bank_radius_m, 0.0, 1e6, "m", true);
    check_range("elevation_amplitude_m", p.elevation_amplitude_m, 0.0, 50.0, "m");
    check_range("wall_height_m", p.wall_height_m, 0.0, 20.0, "m", true);
    check_range("wall_thickness_m", p.wall_thickness_m, 0.0, 10.0, "m", true);
    check_range("min_turn_radius_m", p.min_turn_radius_m, 0.0, 1e5, "m", true);
    check_range("edge_tight_m", p.edge_tight_m, 0.05, 100.0, "m");
    check_range("edge_straight_m", p.edge_straight_m, 0.05, 100.0, "m");
    check_range("tight_radius_m", p.tight_radius_m, 0.0, 1e6, "m", true);
    check_range("chunk_length_m", p.chunk_length_m, 0.0, 1e6, "m", true);
    if (p.strips < 1 || p.strips > 256) fail("strips", "must be in [1, 256]", p.strips);

    if (p.edge_straight_m < p.edge_tight_m)
        fail("edge_straight_m", "must be >= edge_tight_m (" + exact_text(p.edge_tight_m) + " m)",
             p.edge_straight_m);
    if (p.chunk_length_m < 4.0 * p.edge_straight_m)
        fail("chunk_length_m",
             "must be at least 4 x edge_straight_m (" + exact_text(4.0 * p.edge_straight_m) + " m)",
             p.chunk_length_m);

    // Two parts of the track keep a clearance of both roads with walls and a gap between
    // them; a turn may bring its own two sides that close only if it is at least half
    // that radius, which also keeps its inner edge (w/2 + wall inside) from folding.
    const double clearance = track_detail::required_clearance(p);
    if (p.min_turn_radius_m < 0.5 * clearance)
        fail("min_turn_radius_m",
             "must be at least 0.75 x width_m + wall_thickness_m (" + exact_text(0.5 * clearance) +
                 " m) so that a turn's inner edge does not fold and its two sides keep clear",
             p.min_turn_radius_m);
    // A circle is the generator's last resort; it must itself be a valid track, with room
    // for the Catmull-Rom wobble of a few percent.
    if (p.length_m < 2.0 * std::numbers::pi * 1.5 * p.min_turn_radius_m)
        fail("length_m",
             "is too short for min_turn_radius_m: needs at least 3 pi x min_turn_radius_m (" +
                 exact_text(3.0 * std::numbers::pi * p.min_turn_radius_m) + " m)",
             p.length_m);

    // Upper bound of the rows (all at the tight spacing on the outer edge of the tightest
    // allowed turn: ds = edge / (1 + w / 2R)) times the triangles of one row step.
    const double rows = p.length_m * (1.0 + 0.5 * p.width_m / p.min_turn_radius_m) / p.edge_tight_m;
    const double triangles = rows * 2.0 * (p.strips + 6);
    if (triangles > kTriangleBudget)
        fail("edge_tight_m",
             "makes the track too dense: up to " + std::to_string(triangles) +
                 " triangles, more than the budget of " + std::to_string(kTriangleBudget) +
                 " (raise edge_tight_m, lower strips or length_m)",
             p.edge_tight_m);
}

}  // namespace trackphys
