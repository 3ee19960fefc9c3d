// Oracle tests of the stick-slip Coulomb friction of the gimbal plants (sim/drives/gimbal_bearings.hpp in
// sim/models/gimbal_gyro.hpp and sim/models/gyro_vertical.hpp) against Magnus, *Kreisel*, §11.2.2 and
// §12.3.1:
//   gimbal gyro: the stick/slip threshold — a torque M1 ≤ r1 on a gyro at rest moves nothing (no precession),
//   a torque above it drifts at the mean rate (M1 − r1)/H of (11.11)-(11.15) — with RK4 at 0.1 ms and with
//   the gyroscopic exponential at the 1 ms controller tick; the smooth model creeps under the same
//   sub-threshold torque;
//   gyro vertical with the linear correction (rows 3 + 4 of (12.35)): the dead zone of Fig. 12.12 — every
//   point of the band |f2 α| ≤ r2, |f1 β| ≤ r1 is an equilibrium (stuck, not moving in an hour), a tilt
//   outside it erects onto the band's corner (r2/f2, r1/f1) and stops there; the smooth model creeps.
// Why exact zeros: a held axis gets the friction −τ_a of its own net torque at the step start; with static
// torques the stage accelerations are rounding (≲ 1e-16 of the torque over the inertia), so in 1e7 steps
// the angles move by ≲ 1e-18 rad — below one ulp of the angle. The tolerance 1e-15 rad is that ulp scale.
// Docs: docs/models/gimbal-gyro.md#coulomb-friction-stick-slip, docs/models/gyro-vertical.md#the-dead-zone.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <tuple>

#include "firmware/control/gyro_vertical_correction.hpp"
#include "sim/dynamics/gyroscopic_exponential.hpp"
#include "sim/dynamics/rk4.hpp"
#include "sim/models/gimbal_gyro.hpp"
#include "sim/models/gyro_vertical.hpp"

namespace gyrostab {
namespace gimbal_stick_slip_test {

using Gyro = models::GimbalGyro<models::FixedBase>;
using drives::CoulombModel;
using models::GyroVertical;
using models::GyroVerticalParams;

// An instrument gyro: H = 0.5 N m s, A = 2e-3, B = 1.5e-3 kg m² (ω_N = H/sqrt(AB) = 289 rad/s), bearing
// friction r1 = r2 = 1e-3 N m, no gravity; the outer axis vertical so β is the only angle in I(β).
models::GimbalGyroParams instrument_gyro(CoulombModel model) {
  models::GimbalGyroParams p;
  p.AR = 1.5e-3;
  p.AA = 0.5e-3;
  p.CR = 1e-3;
  p.r1 = p.r2 = 1e-3;
  p.friction_model = model;
  return p;
}
constexpr double kH = 0.5;
const models::FixedBase kVerticalOuterAxis{dynamics::Vec3::UnitX()};

struct Drift {
  double alpha, beta;  // change over the run [rad]
  double beta_rate;    // mean β' over the run's second half [rad/s]
};

// RK4 at h = 1e-4 s (h ω_N = 0.029) from rest at (α, β) = (0, 0.1) under a constant M1.
Drift run_gyro(CoulombModel model, double M1, double T) {
  Gyro g(instrument_gyro(model), kVerticalOuterAxis);
  g.torques.M1 = M1;
  Gyro::State x = Gyro::make_state(0.0, 0.1, 0.0, 0.0, kH);
  dynamics::Rk4<Gyro> integ(g);
  const double h = 1e-4;
  const auto n = static_cast<long>(T / h + 0.5);
  double beta_half = 0.0;
  for (long i = 0; i < n; ++i) {
    integ.step(static_cast<double>(i) * h, h, x);
    if (i + 1 == n / 2) beta_half = x[1];
  }
  return {x[0], x[1] - 0.1, (x[1] - beta_half) / (0.5 * T)};
}

TEST(GimbalGyroStickSlip, TorqueBelowFrictionMovesNothingWhereTheSmoothModelCreeps) {
  const double r1 = 1e-3, M1 = 0.9 * r1, T = 600.0;
  const Drift stick = run_gyro(CoulombModel::kStickSlip, M1, T);
  const Drift smooth = run_gyro(CoulombModel::kSmooth, M1, T);
  std::printf("M1 = 0.9 r1 for %g s: stick-slip moved (%.3g, %.3g) rad, smooth (%.3g, %.3g) rad\n", T,
              stick.alpha, stick.beta, smooth.alpha, smooth.beta);
  // Held to rounding (the header's budget): no precession under a torque below friction.
  EXPECT_LE(std::fabs(stick.alpha), 1e-15);
  EXPECT_LE(std::fabs(stick.beta), 1e-15);
  // The smooth law is viscous r/v_c = 10 N m s/rad below v_c ≫ H: the gimbal creeps at ≈ M1 v_c/r = 9e-5
  // rad/s about axis 1, 0.05 rad in 10 min (≥ 0.01 rad asserted: 5× margin on that estimate).
  EXPECT_GT(std::hypot(smooth.alpha, smooth.beta), 1e-2);
}

TEST(GimbalGyroStickSlip, TorqueAboveFrictionDriftsAtMMinusROverH) {
  // (11.11)-(11.15): above the threshold the singular points of the phase plane lie in one half-plane; the
  // motion is an undamped nutation on a steady drift β' = (M1 − r1)/(H cosβ) (axis 2 precessing, axis 1
  // slipping at r2/(H cosβ) against the bearing). Over 20 s β moves by 0.04 rad: cosβ within 0.4 % of its
  // mid-run value, which sets the 1 % tolerance; the nutation's share of the mean, amplitude/(ω_N T/2) ≈
  // 4e-3/(289 · 10), is 1e-6 rad/s.
  const double r1 = 1e-3, T = 20.0;
  for (const double M1 : {1.5 * r1, 3.0 * r1}) {
    const Drift d = run_gyro(CoulombModel::kStickSlip, M1, T);
    const double beta_mid = 0.1 + 0.75 * d.beta;
    const double predicted = (M1 - r1) / (kH * std::cos(beta_mid));
    std::printf("M1 = %.1f r1: mean beta' %.6g rad/s, (M1 - r1)/(H cos beta) = %.6g\n", M1 / r1, d.beta_rate,
                predicted);
    EXPECT_NEAR(d.beta_rate / predicted, 1.0, 1e-2) << "M1 = " << M1;
  }
  // At 0.99 r1 it stays: the threshold is r1 itself, not a neighbourhood of it.
  const Drift below = run_gyro(CoulombModel::kStickSlip, 0.99 * r1, 10.0);
  EXPECT_LE(std::fabs(below.beta), 1e-15);
}

TEST(GimbalGyroStickSlip, TheThresholdHoldsWithTheGyroscopicExponentialAtOneMillisecond) {
  // The integrator the gimbal scenes run at the controller tick (h ω_N = 0.29 here): the friction is a
  // forcing held over the step, which the exponential flow takes exactly for a constant torque.
  const double r1 = 1e-3;
  for (const double M1 : {0.9 * r1, 1.5 * r1, 3.0 * r1}) {
    Gyro g(instrument_gyro(CoulombModel::kStickSlip), kVerticalOuterAxis);
    g.torques.M1 = M1;
    Gyro::State x = Gyro::make_state(0.0, 0.1, 0.0, 0.0, kH);
    dynamics::GyroscopicExponential<Gyro> integ(g);
    const double h = 1e-3, T = 20.0;
    double beta_half = 0.0;
    for (int i = 0; i < 20000; ++i) {
      integ.step(i * h, h, x);
      if (i + 1 == 10000) beta_half = x[1];
    }
    const double rate = (x[1] - beta_half) / (0.5 * T);
    const double predicted = M1 > r1 ? (M1 - r1) / (kH * std::cos(0.1 + 0.75 * (x[1] - 0.1))) : 0.0;
    std::printf(
        "gyro-exponential 1 ms, M1 = %.1f r1: moved (%.3g, %.3g) rad, mean beta' %.6g (predicted %.6g)\n",
        M1 / r1, x[0], x[1] - 0.1, rate, predicted);
    if (M1 <= r1) {
      EXPECT_LE(std::fabs(x[0]), 1e-15);
      EXPECT_LE(std::fabs(x[1] - 0.1), 1e-15);
    } else {
      // Tolerances as in the RK4 test: 1 % on β'; axis 1 slips at r2/(H cosβ) (the singular point α'*0 of
      // (11.11)-(11.15)), 2 % on α over the whole run (its start-up transient included).
      EXPECT_NEAR(rate / predicted, 1.0, 1e-2);
      EXPECT_NEAR(x[0] / (1e-3 * T / (kH * std::cos(0.1 + 0.5 * (x[1] - 0.1)))), 1.0, 2e-2);
    }
  }
}

// ---- gyro vertical: rows 3 + 4 of (12.35), the firmware's linear correction sampled at 1 kHz (as the
// firmware runs it), plant friction r1 = r2 = 4e-4 N m, f1 = f2 = 0.02 N m/rad: the band r/f = 0.02 rad.
constexpr double kR = 4e-4, kF = 0.02, kBand = kR / kF;

struct Vertical {
  GyroVertical g;
  firmware::GyroVerticalCorrectionParams law;
};

Vertical make_vertical(CoulombModel model) {
  GyroVerticalParams p;
  p.gyro = {2e-3, 2e-3, kH};  // ω_N = 250 rad/s
  p.c = 0.0;
  p.d1 = p.d2 = 2e-3;  // d/A = 1 /s > δ = f/H = 0.04 /s: the nutation decays (model header)
  p.r1 = p.r2 = kR;
  p.friction_model = model;
  Vertical v{GyroVertical(p), {}};
  v.g.inputs.frame.hold({dynamics::Vec3::Zero(), dynamics::Vec3::Zero(), dynamics::Vec3(0, 0, -9.81)});
  v.law.H = kH;
  v.law.f1 = v.law.f2 = kF;
  v.law.torque_limit_Nm = 1.0;
  return v;
}

// Runs [0, T] at the 1 kHz tick with 4 RK4 sub-steps.
GyroVertical::State run_vertical(Vertical& v, GyroVertical::State x, double T) {
  dynamics::Rk4<GyroVertical> integ(v.g);
  const double tick = 1e-3;
  const auto n = static_cast<long>(T / tick + 0.5);
  for (long k = 0; k < n; ++k) {
    firmware::CorrectionSignals s;
    v.g.erection_signal(static_cast<double>(k) * tick, x, s.e1, s.e2);
    s.alpha_rate = x[2];
    s.beta_rate = x[3];
    const firmware::CorrectionTorques m = firmware::gyro_vertical_correction(v.law, s);
    v.g.inputs.M1 = m.M1;
    v.g.inputs.M2 = m.M2;
    for (int j = 0; j < 4; ++j) integ.step(static_cast<double>(k) * tick + j * tick / 4, tick / 4, x);
  }
  return x;
}

TEST(GyroVerticalStickSlip, InsideTheDeadZoneTheErectionStopsWhereTheSmoothModelCreeps) {
  // Fig. 12.12: inside the band the correction's torques (≤ f · band = r) cannot overcome the bearings; the
  // gyro stays where it is. One hour from the first point (the smooth model's below), 10 min from two more
  // (one near the band's corner).
  for (const auto& [a0, b0, T] :
       {std::tuple{0.5 * kBand, -0.7 * kBand, 3600.0}, std::tuple{-0.2 * kBand, 0.1 * kBand, 600.0},
        std::tuple{0.98 * kBand, 0.98 * kBand, 600.0}}) {
    Vertical v = make_vertical(CoulombModel::kStickSlip);
    const GyroVertical::State x = run_vertical(v, GyroVertical::make_state(a0, b0), T);
    EXPECT_LE(std::fabs(x[0] - a0), 1e-15) << a0 << ", " << b0;
    EXPECT_LE(std::fabs(x[1] - b0), 1e-15) << a0 << ", " << b0;
  }
  // The smooth law (ε = 1e-4 rad/s) is viscous r/ε = 4 N m s/rad below ε, and every rate here is below
  // ε: the correction keeps erecting through the band, only slower, and after an hour the gyro has crept
  // most of the way to the origin (measured: 0.0165 rad of travel; ≥ half the band's half-width asserted).
  Vertical s = make_vertical(CoulombModel::kSmooth);
  const GyroVertical::State xs = run_vertical(s, GyroVertical::make_state(0.5 * kBand, -0.7 * kBand), 3600.0);
  std::printf("smooth model after 1 h from inside the band: alpha %.4f beta %.4f rad (band %.3f)\n", xs[0],
              xs[1], kBand);
  EXPECT_GT(std::hypot(xs[0] - 0.5 * kBand, xs[1] + 0.7 * kBand), 0.5 * kBand);
}

TEST(GyroVerticalStickSlip, OutsideTheDeadZoneItErectsOntoTheBandsCorner) {
  // From (α, β) = (0.15, −0.1) rad the precession with friction ((11.16)-(11.18) with the correction for c)
  // runs straight to the singular point of its quadrant, the corner (r2/f2, r1/f1) (α' < 0, β' > 0 there),
  // approaching it as e^(−f t/H), 25 s: after 600 s, 0.13 e^(−24) = 5e-12 rad away in the precession theory.
  // The corner is marginal — the correction's torque on axis 1 equals r1 there — so the axes do not both
  // stick: axis 2 holds at the edge and axis 1 keeps the rate it had when axis 2 entered the Karnopp band,
  // below v_st = 1e-9 rad/s (measured 5.5e-10). Tolerance on the corner: 1e-6 rad (the slide over 600 s is
  // ≤ 6e-7; measured distance 1e-7). In the following hour it moves ≤ 3600 s · v_st = 3.6e-6 rad along the
  // band's edge (measured 1.9e-6) — against 0.0165 rad for the smooth model from inside the band.
  const double v_st = GyroVerticalParams{}.stick_rate;
  Vertical v = make_vertical(CoulombModel::kStickSlip);
  const GyroVertical::State x = run_vertical(v, GyroVertical::make_state(0.15, -0.1), 600.0);
  std::printf("erected from (0.15, -0.1): alpha %.9f beta %.9f rad, corner (%.4f, %.4f)\n", x[0], x[1], kBand,
              kBand);
  EXPECT_NEAR(x[0], kBand, 1e-6);
  EXPECT_NEAR(x[1], kBand, 1e-6);
  const GyroVertical::State y = run_vertical(v, x, 3600.0);
  std::printf("the hour after: moved (%.3g, %.3g) rad\n", y[0] - x[0], y[1] - x[1]);
  EXPECT_LE(std::hypot(y[0] - x[0], y[1] - x[1]), 3600.0 * v_st);
  // Just outside the band on one axis it moves: from (1.2 r2/f2, 0) axis 2 breaks away, the gyroscopic
  // torque H β' then frees axis 1, and the point erects onto the same corner.
  Vertical w = make_vertical(CoulombModel::kStickSlip);
  const GyroVertical::State z = run_vertical(w, GyroVertical::make_state(1.2 * kBand, 0.0), 600.0);
  std::printf("from (1.2 band, 0): alpha %.9f beta %.9f rad\n", z[0], z[1]);
  EXPECT_NEAR(z[0], kBand, 1e-6);
  EXPECT_NEAR(z[1], kBand, 1e-6);
}

}  // namespace gimbal_stick_slip_test
}  // namespace gyrostab
