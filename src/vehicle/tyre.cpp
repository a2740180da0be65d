#include "trackphys/vehicle/tyre.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <mutex>
#include <numbers>
#include <sstream>

#include "trackphys/error.hpp"

namespace trackphys {

double MagicFormulaCurve::peak(double load, double nominal_load) const {
    const double dfz = std::min((load - nominal_load) / nominal_load, kMaxLoadRatio - 1.0);
    return std::max(0.0, friction * (1.0 + friction_load_slope * dfz) * load);
}

double MagicFormulaCurve::force(double slip, double peak_force) const {
    const double bx = stiffness * slip;
    return peak_force * std::sin(shape * std::atan(bx - curvature * (bx - std::atan(bx))));
}

double MagicFormulaCurve::peak_slip() const {
    if (std::string why = validate("MagicFormulaCurve."); !why.empty()) throw Error(why);
    // sin peaks where C atan(Phi) = pi/2. Phi(u) = (1 - E) u + E atan(u), u = B x, rises
    // monotonically from 0 for E <= 1, so bisection on u finds the one crossing.
    const double target = std::tan(0.5 * std::numbers::pi / shape);
    const auto phi = [&](double u) { return (1.0 - curvature) * u + curvature * std::atan(u); };
    double low = 0.0;
    double high = 1.0;
    while (phi(high) < target) high *= 2.0;
    for (int i = 0; i < 200 && high - low > 1e-15 * high; ++i) {
        const double mid = 0.5 * (low + high);
        (phi(mid) < target ? low : high) = mid;
    }
    return 0.5 * (low + high) / stiffness;
}

std::string MagicFormulaCurve::validate(const std::string& prefix) const {
    std::ostringstream why;
    const auto positive = [&](const char* field, double value) {
        if (why.tellp() == 0 && !(std::isfinite(value) && value > 0.0))
            why << prefix << field << " must be finite and > 0, got " << exact_text(value);
    };
    positive("stiffness", stiffness);
    positive("friction", friction);
    // C in (1, 2]: the curve rises to a peak at C atan(Phi) = pi/2 and stays >= 0 beyond.
    if (why.tellp() == 0 && !(shape > 1.0 && shape <= 2.0))
        why << prefix << "shape must be in (1, 2], got " << exact_text(shape);
    if (why.tellp() == 0 && !(std::isfinite(curvature) && curvature <= 1.0))
        why << prefix << "curvature must be finite and <= 1, got " << exact_text(curvature);
    // With E = 1, Phi = atan(u) < pi/2 never reaches tan(pi / 2C) when C is near 1: it
    // does for C > pi / (2 atan(pi/2)) = 1.5647.
    if (why.tellp() == 0 && curvature == 1.0 &&
        !(std::tan(0.5 * std::numbers::pi / shape) < 0.5 * std::numbers::pi))
        why << prefix << "shape must exceed 1.565 when curvature is 1 (no peak), got "
            << exact_text(shape);
    // The friction must stay > 0 over the whole load range: mu (1 + slope (kMaxLoadRatio - 1))
    // at its top (lowest_friction(), which an autopilot plans its turns from).
    const double range = kMaxLoadRatio - 1.0;
    if (why.tellp() == 0 && !(std::isfinite(friction_load_slope) && friction_load_slope <= 0.0 &&
                              friction_load_slope * range > -1.0))
        why << prefix << "friction_load_slope must be in (" << exact_text(-1.0 / range)
            << ", 0] (the friction at " << kMaxLoadRatio << " times the nominal load, mu (1 + "
            << range << " slope), must stay > 0), got " << exact_text(friction_load_slope);
    return why.str();
}

TyreSpec TyreSpec::road() {
    TyreSpec tyre;
    tyre.longitudinal = {10.0, 1.9, 0.97, 1.0, -0.1};
    tyre.lateral = {10.0, 1.9, 0.97, 1.0, -0.1};
    tyre.nominal_load = 4000.0;
    tyre.longitudinal_relaxation = 0.15;
    tyre.lateral_relaxation = 0.35;
    return tyre;
}

TyreSpec TyreSpec::slick() {
    TyreSpec tyre;
    tyre.longitudinal = {20.0, 1.65, 0.3, 1.6, -0.1};
    tyre.lateral = {20.0, 1.4, 0.3, 1.6, -0.1};
    tyre.nominal_load = 3500.0;
    tyre.longitudinal_relaxation = 0.1;
    tyre.lateral_relaxation = 0.25;
    return tyre;
}

std::string TyreSpec::validate(const std::string& prefix) const {
    if (std::string why = longitudinal.validate(prefix + "longitudinal."); !why.empty()) return why;
    if (std::string why = lateral.validate(prefix + "lateral."); !why.empty()) return why;
    std::ostringstream why;
    const auto positive = [&](const char* field, double value) {
        if (why.tellp() == 0 && !(std::isfinite(value) && value > 0.0))
            why << prefix << field << " must be finite and > 0, got " << exact_text(value);
    };
    positive("nominal_load", nominal_load);
    positive("longitudinal_relaxation", longitudinal_relaxation);
    positive("lateral_relaxation", lateral_relaxation);
    return why.str();
}

namespace {

TyreSpec validated(const TyreSpec& spec) {
    if (std::string why = spec.validate("TyreSpec."); !why.empty()) throw Error(why);
    return spec;
}

using ShapeTable = std::vector<double>;

ShapeTable shape_table(const MagicFormulaCurve& curve, double peak_slip) {
    ShapeTable table(Tyre::kTableSpan * Tyre::kTableSteps + 1);
    for (std::size_t k = 0; k < table.size(); ++k)
        table[k] = curve.force(static_cast<double>(k) / Tyre::kTableSteps * peak_slip, 1.0);
    return table;
}

// The table of every curve with curve's B, C and E (its peak slip follows from them): 16
// KB each, built once while a tyre holds it, so that a race of identical cars shares one
// per curve in the cache, and a rear tyre that only grips more shares the front's. The
// shape over the normalised slip does not depend on B, but its last bits do: keyed on B
// too, a vehicle's results never depend on which tyre built the table first.
std::shared_ptr<const ShapeTable> shared_shape_table(const MagicFormulaCurve& curve,
                                                     double peak_slip) {
    using Key = std::array<double, 3>;
    static std::mutex mutex;
    static std::map<Key, std::weak_ptr<const ShapeTable>> tables;
    const Key key{curve.stiffness, curve.shape, curve.curvature};
    const std::lock_guard lock(mutex);
    if (const auto found = tables.find(key); found != tables.end())
        if (std::shared_ptr<const ShapeTable> table = found->second.lock()) return table;
    std::erase_if(tables, [](const auto& entry) { return entry.second.expired(); });
    auto table = std::make_shared<const ShapeTable>(shape_table(curve, peak_slip));
    tables[key] = table;
    return table;
}

// F / D of curve at normalised slip s >= 0, from its table (peak_slip: the curve's).
double shape_at(const ShapeTable& table, const MagicFormulaCurve& curve, double peak_slip,
                double s) {
    const double u = s * Tyre::kTableSteps;
    if (!(u < Tyre::kTableSpan * Tyre::kTableSteps)) return curve.force(s * peak_slip, 1.0);
    const auto k = static_cast<std::size_t>(u);
    const double t = u - static_cast<double>(k);
    return table[k] + t * (table[k + 1] - table[k]);
}

}  // namespace

Tyre::Tyre(const TyreSpec& spec)
    : spec_(validated(spec)),
      peak_slip_ratio_(spec.longitudinal.peak_slip()),
      peak_lateral_slip_(spec.lateral.peak_slip()),
      inverse_peak_slip_ratio_(1.0 / peak_slip_ratio_),
      inverse_peak_lateral_slip_(1.0 / peak_lateral_slip_),
      longitudinal_shape_(shared_shape_table(spec.longitudinal, peak_slip_ratio_)),
      lateral_shape_(shared_shape_table(spec.lateral, peak_lateral_slip_)) {}

TyreForce Tyre::peaks(double load, double road_grip) const {
    return {road_grip * spec_.longitudinal.peak(load, spec_.nominal_load),
            road_grip * spec_.lateral.peak(load, spec_.nominal_load)};
}

TyreForce Tyre::force(double slip_ratio, double lateral_slip, double load, double road_grip) const {
    if (!(load > 0.0)) return {};
    return force(slip_ratio, lateral_slip, peaks(load, road_grip));
}

TyreForce Tyre::force(double slip_ratio, double lateral_slip, const TyreForce& peak) const {
    return force(normalised(slip_ratio, lateral_slip), peak);
}

NormalisedSlip Tyre::normalised(double slip_ratio, double lateral_slip) const {
    const double sx = slip_ratio * inverse_peak_slip_ratio_;
    const double sy = lateral_slip * inverse_peak_lateral_slip_;
    return {sx, sy, std::sqrt(sx * sx + sy * sy)};  // bounded slips: no hypot needed
}

TyreForce Tyre::force(const NormalisedSlip& slip, const TyreForce& peak) const {
    const double s = slip.combined;
    if (s == 0.0) return {};
    const double fx =
        peak.longitudinal * shape_at(*longitudinal_shape_, spec_.longitudinal, peak_slip_ratio_, s);
    const double fy =
        peak.lateral * shape_at(*lateral_shape_, spec_.lateral, peak_lateral_slip_, s);
    const double share = 1.0 / s;  // one division for both directions
    return {fx * (slip.longitudinal * share), fy * (slip.lateral * share)};
}

}  // namespace trackphys
