// The Magic Formula tyre: each shipped curve peaks where its coefficients say, and the
// combined-slip force never leaves the friction ellipse.
#include "trackphys/vehicle/tyre.hpp"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "trackphys/error.hpp"

namespace trackphys {
namespace {

struct NamedTyre {
    const char* name;
    TyreSpec spec;
};

const NamedTyre kTyres[] = {{"road", TyreSpec::road()}, {"slick", TyreSpec::slick()}};

// The slip of the largest force among fine samples of the curve: found by search, not by
// the formula's closed form that peak_slip() solves.
double sampled_peak_slip(const MagicFormulaCurve& curve) {
    double best_slip = 0.0;
    double best_force = 0.0;
    for (int i = 1; i <= 200000; ++i) {
        const double slip = 1e-5 * i;
        const double force = curve.force(slip, 1.0);
        if (force > best_force) best_force = force, best_slip = slip;
    }
    return best_slip;
}

TEST(Tyre, EachCurvePeaksWhereItsCoefficientsSay) {
    for (const NamedTyre& tyre : kTyres) {
        for (const MagicFormulaCurve* curve : {&tyre.spec.longitudinal, &tyre.spec.lateral}) {
            SCOPED_TRACE(tyre.name);
            const double peak = curve->peak_slip();
            EXPECT_NEAR(sampled_peak_slip(*curve), peak, 2e-5);
            // At its peak the curve reaches D, and falls on either side.
            const double load = 3000.0;
            const double d = curve->peak(load, tyre.spec.nominal_load);
            EXPECT_NEAR(curve->force(peak, d), d, 1e-9 * d);
            EXPECT_LT(curve->force(0.8 * peak, d), d);
            EXPECT_LT(curve->force(1.5 * peak, d), d);
            // Odd in the slip: braking mirrors driving.
            EXPECT_DOUBLE_EQ(curve->force(-0.5 * peak, d), -curve->force(0.5 * peak, d));
        }
    }
}

TEST(Tyre, PeakFrictionFallsWithLoadAsTheSlopeSays) {
    for (const NamedTyre& tyre : kTyres) {
        SCOPED_TRACE(tyre.name);
        const MagicFormulaCurve& curve = tyre.spec.lateral;
        const double fz0 = tyre.spec.nominal_load;
        EXPECT_DOUBLE_EQ(curve.peak(fz0, fz0), curve.friction * fz0);
        const double mu_double = curve.peak(2.0 * fz0, fz0) / (2.0 * fz0);
        EXPECT_NEAR(mu_double, curve.friction * (1.0 + curve.friction_load_slope), 1e-12);
        EXPECT_LT(mu_double, curve.friction);
        // Beyond the load range the friction coefficient holds its value at the edge.
        const double edge = MagicFormulaCurve::kMaxLoadRatio * fz0;
        EXPECT_NEAR(curve.peak(2.0 * edge, fz0) / (2.0 * edge), curve.peak(edge, fz0) / edge,
                    1e-12);
        EXPECT_DOUBLE_EQ(curve.peak(edge, fz0) / edge, curve.lowest_friction());
    }
}

// How far Tyre::force's tabulated curve shapes may stray from the formula, over the peak
// force (linear interpolation, Tyre::kTableSteps nodes per unit of normalised slip).
constexpr double kTableError = 2e-5;

TEST(Tyre, TabulatedCurvesFollowTheFormulaAndKeepThePeaks) {
    for (const NamedTyre& tyre : kTyres) {
        SCOPED_TRACE(tyre.name);
        const Tyre model(tyre.spec);
        const double fz = tyre.spec.nominal_load;
        const double dx = tyre.spec.longitudinal.peak(fz, fz);
        const double dy = tyre.spec.lateral.peak(fz, fz);
        // At each peak exactly the peak force: a node sits there.
        EXPECT_DOUBLE_EQ(model.force(model.peak_slip_ratio(), 0.0, fz).longitudinal, dx);
        EXPECT_DOUBLE_EQ(model.force(0.0, model.peak_lateral_slip(), fz).lateral, dy);
        // Between the nodes and beyond the table's span (the formula there).
        for (int i = 0; i <= 40000; ++i) {
            const double s = 10.0 * i / 40000.0;
            const double kappa = s * model.peak_slip_ratio();
            const double alpha = s * model.peak_lateral_slip();
            ASSERT_NEAR(model.force(kappa, 0.0, fz).longitudinal,
                        tyre.spec.longitudinal.force(kappa, dx), kTableError * dx)
                << "s " << s;
            ASSERT_NEAR(model.force(0.0, alpha, fz).lateral, tyre.spec.lateral.force(alpha, dy),
                        kTableError * dy)
                << "s " << s;
        }
    }
}

// Tyres share their shape tables by curve: one whose shape or curvature factor differs,
// built while another tyre holds its table, must still follow its own formula, to 1e-3 of
// its peak (kTableError is for the shipped sets): the held tyre's table would be off by
// 1.4e-3 for the curvature, 2e-2 for the shape.
TEST(Tyre, ACurveOfAnotherShapeGetsItsOwnTable) {
    const TyreSpec slick = TyreSpec::slick();
    const Tyre held(slick);
    for (double MagicFormulaCurve::*factor :
         {&MagicFormulaCurve::shape, &MagicFormulaCurve::curvature}) {
        TyreSpec other = slick;
        other.lateral.*factor *= 0.9;
        const Tyre model(other);
        const double fz = other.nominal_load;
        const double dy = other.lateral.peak(fz, fz);
        for (int i = 1; i <= 400; ++i) {
            const double alpha = 4.0 * i / 400.0 * model.peak_lateral_slip();
            ASSERT_NEAR(model.force(0.0, alpha, fz).lateral, other.lateral.force(alpha, dy),
                        1e-3 * dy)
                << "alpha " << alpha;
        }
    }
}

TEST(Tyre, CombinedForceStaysInTheFrictionEllipseAndPureSlipIsTheCurve) {
    std::mt19937 random(20);
    std::uniform_real_distribution<double> slip(-1.0, 1.0);
    std::uniform_real_distribution<double> load(100.0, 12000.0);
    for (const NamedTyre& tyre : kTyres) {
        SCOPED_TRACE(tyre.name);
        const Tyre model(tyre.spec);
        for (int i = 0; i < 20000; ++i) {
            // Spread the slips over small and large multiples of the peaks.
            const double scale = std::pow(10.0, 2.0 * slip(random));
            const double kappa = slip(random) * scale * model.peak_slip_ratio();
            const double alpha = slip(random) * scale * model.peak_lateral_slip();
            const double fz = load(random);
            const TyreForce f = model.force(kappa, alpha, fz);
            const double dx = tyre.spec.longitudinal.peak(fz, tyre.spec.nominal_load);
            const double dy = tyre.spec.lateral.peak(fz, tyre.spec.nominal_load);
            const double ellipse = std::pow(f.longitudinal / dx, 2) + std::pow(f.lateral / dy, 2);
            ASSERT_LE(ellipse, 1.0 + 1e-12) << "kappa " << kappa << " alpha " << alpha;
            // Forces oppose nothing: they point the way their slips do.
            EXPECT_GE(f.longitudinal * kappa, 0.0);
            EXPECT_GE(f.lateral * alpha, 0.0);
            // Pure slip is the curve itself, to the shape table's accuracy.
            EXPECT_NEAR(model.force(kappa, 0.0, fz).longitudinal,
                        tyre.spec.longitudinal.force(kappa, dx), kTableError * dx);
            EXPECT_NEAR(model.force(0.0, alpha, fz).lateral, tyre.spec.lateral.force(alpha, dy),
                        kTableError * dy);
        }
        // At both peaks at once the force lies on the ellipse, not beyond.
        const TyreForce both =
            model.force(model.peak_slip_ratio(), model.peak_lateral_slip(), 4000.0);
        const double dx = tyre.spec.longitudinal.peak(4000.0, tyre.spec.nominal_load);
        const double dy = tyre.spec.lateral.peak(4000.0, tyre.spec.nominal_load);
        EXPECT_LT(std::pow(both.longitudinal / dx, 2) + std::pow(both.lateral / dy, 2), 1.0);
    }
}

TEST(Tyre, InvalidCoefficientsNameTheField) {
    TyreSpec spec = TyreSpec::road();
    spec.lateral.curvature = 1.5;
    EXPECT_EQ(spec.validate("front_tyre."),
              "front_tyre.lateral.curvature must be finite and <= 1, got 1.5");
    spec = TyreSpec::slick();
    spec.longitudinal.shape = 0.9;
    EXPECT_THROW(Tyre{spec}, Error);
    spec = TyreSpec::road();
    spec.lateral_relaxation = 0.0;
    EXPECT_NE(spec.validate("t.").find("t.lateral_relaxation"), std::string::npos);
}

// The friction must stay > 0 up to the top of the load range (3 F_z0): a slope at or below
// -0.5 leaves the tyre no grip there, which an autopilot planning from lowest_friction()
// would take for a road it cannot turn on.
TEST(Tyre, ALoadSlopeThatLosesAllGripInTheLoadRangeIsRefused) {
    TyreSpec spec = TyreSpec::road();
    spec.lateral.friction_load_slope = -0.4999;
    EXPECT_EQ(spec.validate("t."), "");
    EXPECT_GT(spec.lateral.lowest_friction(), 0.0);
    for (const double slope : {-0.5, -0.6, -0.9}) {
        spec.lateral.friction_load_slope = slope;
        EXPECT_EQ(spec.validate("t."),
                  "t.lateral.friction_load_slope must be in (-0.5, 0] (the friction at 3 times "
                  "the nominal load, mu (1 + 2 slope), must stay > 0), got " +
                      exact_text(slope));
    }
}

}  // namespace
}  // namespace trackphys
