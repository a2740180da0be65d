#pragma once

#include <memory>
#include <string>
#include <vector>

#include "trackphys/export.hpp"

namespace trackphys {

/// One direction of a tyre's steady-state force curve, Pacejka's four-coefficient Magic
/// Formula with MF 5.2's linear load sensitivity of the friction coefficient
/// (docs/vehicle.md):
///
///     F(x) = D sin(C atan(B x - E (B x - atan(B x)))),   D = mu (1 + mu_load dfz) F_z,
///
/// where x is the slip (slip ratio, or the tangent of the slip angle) and
/// dfz = (F_z - F_z0) / F_z0 the load's departure from the tyre's nominal load.
struct MagicFormulaCurve {
    double stiffness = 10.0;  ///< B: stiffness factor
    double shape = 1.9;       ///< C: shape factor, in (1, 2] for a curve that peaks
    double curvature = 0.97;  ///< E: curvature factor, <= 1
    double friction = 1.0;    ///< mu: peak force over load at the nominal load
    /// d mu / d dfz over mu: how the peak friction falls as the load rises (MF 5.2's
    /// pD2 / pD1; < 0 for real tyres, which is why a stiff anti-roll bar loses grip).
    double friction_load_slope = 0.0;

    /// The load range over which the friction follows its load slope, as a multiple of
    /// the nominal load: beyond it the friction coefficient stays at its value there, as
    /// MF 5.2 clamps the load to its tyre's measured range (FZMAX). Without it the
    /// parabola mu (1 + slope dfz) F_z would lose grip under more load past 5.5 F_z0.
    static constexpr double kMaxLoadRatio = 3.0;

    /// Peak force D (N) at load F_z (N) for a tyre of nominal load F_z0 (N); never < 0.
    TRACKPHYS_API double peak(double load, double nominal_load) const;
    /// Peak force over load at the top of the load range: the least friction it has.
    double lowest_friction() const {
        return friction * (1.0 + friction_load_slope * (kMaxLoadRatio - 1.0));
    }
    /// F(x) for peak force D (N).
    TRACKPHYS_API double force(double slip, double peak_force) const;
    /// F'(0) = B C D for peak force D (N): the slip stiffness (N per unit slip) that a
    /// damper or a stability bound on the curve reads.
    double slip_stiffness(double peak_force) const { return stiffness * shape * peak_force; }
    /// The slip at which F peaks: where C atan(Phi) = pi/2, solved for x. Throws
    /// trackphys::Error when the curve has no peak (validate() says why).
    TRACKPHYS_API double peak_slip() const;
    /// Empty when the curve has a peak and finite factors; else the first problem, with
    /// the field named after prefix (e.g. "VehicleSpec.front_tyre.lateral.shape ...").
    TRACKPHYS_API std::string validate(const std::string& prefix) const;
};

/// A tyre: its longitudinal and lateral Magic Formula curves, the load they were measured
/// at, and its relaxation lengths (how far it rolls before a slip change builds up to its
/// steady-state force).
struct TyreSpec {
    MagicFormulaCurve longitudinal;
    MagicFormulaCurve lateral;
    double nominal_load = 4000.0;           ///< F_z0, N
    double longitudinal_relaxation = 0.15;  ///< sigma_x, m
    double lateral_relaxation = 0.4;        ///< sigma_y, m

    /// A road tyre (docs/vehicle.md cites the coefficients).
    TRACKPHYS_API static TyreSpec road();
    /// A racing slick (docs/vehicle.md cites the figures it is built from).
    TRACKPHYS_API static TyreSpec slick();

    TRACKPHYS_API std::string validate(const std::string& prefix) const;
};

/// Force of a tyre in its contact frame (N): along its rolling direction and across it.
struct TyreForce {
    double longitudinal = 0.0;
    double lateral = 0.0;
};

/// A tyre's slips normalised by its peak slips (Tyre::force's similarity method): s_x =
/// kappa / kappa_peak, s_y = tan(alpha) / tan(alpha)_peak, and their norm s, 1 where the
/// force reaches the friction ellipse's edge.
struct NormalisedSlip {
    double longitudinal = 0.0;
    double lateral = 0.0;
    double combined = 0.0;
};

/// A validated TyreSpec with its peak slips solved once.
class TRACKPHYS_API Tyre {
  public:
    /// Throws trackphys::Error with TyreSpec::validate()'s message.
    explicit Tyre(const TyreSpec& spec);

    const TyreSpec& spec() const { return spec_; }
    double peak_slip_ratio() const { return peak_slip_ratio_; }
    double peak_lateral_slip() const { return peak_lateral_slip_; }

    /// Combined-slip force at slip ratio kappa and lateral slip tan(alpha) under load F_z
    /// (N), by Pacejka's similarity method: both slips normalised by their peak slips, the
    /// total normalised slip s shared by direction, each force the pure-slip curve at s
    /// times its direction's share. Then (F_x / D_x)^2 + (F_y / D_y)^2 <= 1 always (the
    /// friction ellipse), and each pure-slip curve is reproduced exactly. Positive slips
    /// give positive forces (a wheel spinning faster than it rolls pushes forward; lateral
    /// slip is minus the sideways velocity over the rolling speed).
    /// road_grip scales both peaks: the road's friction relative to the dry road the
    /// curves describe (0.05 for ice).
    /// Unchecked, for the sub-step's sake: the slips must be finite, and so must their
    /// squares (the vehicle model keeps them within +-50; an infinite slip, from a speed
    /// divided by zero, gives NaN), and road_grip > 0 (a negative one reverses the force,
    /// which Vehicle::set_road_grip refuses for that reason).
    TyreForce force(double slip_ratio, double lateral_slip, double load,
                    double road_grip = 1.0) const;
    /// The same force from the peaks (N) that peaks() gives for its load and road: a wheel
    /// that needs the peaks for more than the force computes them once.
    TyreForce force(double slip_ratio, double lateral_slip, const TyreForce& peak) const;
    /// The same force from the normalised slips that normalised() gives: a wheel whose
    /// drivetrain reads them too (anti-lock, traction control) computes them once.
    TyreForce force(const NormalisedSlip& slip, const TyreForce& peak) const;
    /// Each curve's peak force D (N) under load F_z (N) on a road of grip road_grip: the
    /// semi-axes of the friction ellipse.
    TyreForce peaks(double load, double road_grip = 1.0) const;
    /// Slip ratio kappa and lateral slip tan(alpha) over this tyre's peak slips.
    NormalisedSlip normalised(double slip_ratio, double lateral_slip) const;

    /// The combined-slip force tabulates each curve's shape F / D over the normalised slip
    /// s in [0, kTableSpan], kTableSteps a unit apart, linearly interpolated: a node at
    /// s = 1 keeps the peak exact, and the shipped sets stay within 2e-5 D of the formula
    /// (tested); beyond the span the formula itself. The Magic Formula's three
    /// transcendentals per direction were most of the vehicle model's cost per sub-step.
    /// A table depends on its curve's B, C and E only: every Tyre with the same three, in
    /// any vehicle, shares one immutable copy.
    static constexpr int kTableSteps = 256;
    static constexpr int kTableSpan = 8;

  private:
    TyreSpec spec_;
    double peak_slip_ratio_;
    double peak_lateral_slip_;
    double inverse_peak_slip_ratio_;  // multiplied by, not divided by, each sub-step
    double inverse_peak_lateral_slip_;
    using ShapeTable = std::vector<double>;  ///< F / D at s = k / kTableSteps
    std::shared_ptr<const ShapeTable> longitudinal_shape_;
    std::shared_ptr<const ShapeTable> lateral_shape_;
};

}  // namespace trackphys
