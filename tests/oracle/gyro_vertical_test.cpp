// Oracle tests of the gyro vertical (sim/models/gyro_vertical.hpp) under the correction laws of the firmware
// (firmware/control/gyro_vertical_correction.hpp) against Magnus §12.3 (docs/models/gyro-vertical.md):
//   steady turn: the trajectory (12.46) and the equilibrium z_G (12.47); the resonance at ω = −ω^P (its
//   peak |z_G|/α_L = sqrt(δ² + ω^P²)/δ, and the unbounded growth ω^P α_L t at δ = 0 (12.48)); the astatic
//   limits (12.49); the deceleration response (12.41)-(12.42); linear-correction decay with the corrected
//   pairing α ∝ e^(−f2 t/H), β ∝ e^(−f1 t/H) (the book prints f1 and f2 swapped); the Coulomb dead zone
//   (Fig. 12.12) and relay chatter into the origin (Fig. 12.13); the full (nutation) form against the
//   precession form.
// The law is evaluated inside the derivative (continuous feedback, the book's setting), except in the relay
// test, which samples it at 1 kHz like the firmware.
// Step and tolerance: the precession form's modes are ≤ |δ + i(ω + ω^P)| ≈ 0.05 /s; RK4 at h = 0.05 s has
// a local error ~(hλ)^5/120 ≈ 2e-13 per step, ≤ 1e-9 relative over 4e4 steps — tolerances 1e-9 (trajectory)
// and 1e-8 (after a settling of e^-20). The full form's steady state equals the precession form's (the
// inertia terms vanish there); it carries the undamped nutation excited at the start, of amplitude ≲
// (precession rate)/ω^N = 0.02·0.1/250 = 8e-6 rad: tolerance 2e-5 rad.
#include "sim/models/gyro_vertical.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <cstdio>

#include "firmware/control/gyro_vertical_correction.hpp"
#include "sim/dynamics/rk4.hpp"

namespace gyrostab {
namespace gyro_vertical_test {

using C = std::complex<double>;
using models::GyroVertical;
using models::GyroVerticalParams;
constexpr double kG = 9.81;

// The gyro vertical with the firmware law inside the derivative.
struct CorrectedVertical {
  static constexpr int kStateSize = 4;
  using State = GyroVertical::State;
  mutable GyroVertical plant;
  firmware::GyroVerticalCorrectionParams law;

  void derivative(double t, const State& x, State& dx) const {
    firmware::CorrectionSignals s;
    plant.erection_signal(t, x, s.e1, s.e2);
    plant.rates(t, x, s.alpha_rate, s.beta_rate);  // precession form: rates from the uncorrected torques
    if (plant.params().fidelity == models::InstrumentFidelity::kPrecession && (law.d1 > 0 || law.r1 > 0)) {
      ADD_FAILURE() << "rate rows in the precession form need the implicit solve; not used here";
    }
    const firmware::CorrectionTorques m = firmware::gyro_vertical_correction(law, s);
    plant.inputs.M1 = m.M1;
    plant.inputs.M2 = m.M2;
    plant.derivative(t, x, dx);
  }
  void project(State&) const {}
};

// A level turn at rate ω (right > 0) with apparent vertical α_L, or straight flight with forward specific
// force a (book axes forward, right, down).
models::FrameSample turn_frame(double omega, double alpha_L) {
  return {dynamics::Vec3(0, 0, omega), dynamics::Vec3::Zero(), dynamics::Vec3(0, kG * std::tan(alpha_L), -kG)};
}
models::FrameSample straight_frame(double a_forward) {
  return {dynamics::Vec3::Zero(), dynamics::Vec3::Zero(), dynamics::Vec3(a_forward, 0, -kG)};
}

struct Case {
  double H{0.5}, c{2.5e-3}, f{0.01};
  double d{0.0};  // plant bearing damping (both axes)
  models::InstrumentFidelity fidelity{models::InstrumentFidelity::kPrecession};
};

CorrectedVertical make(const Case& s) {
  GyroVerticalParams p;
  p.gyro = {2e-3, 2e-3, s.H};
  p.c = s.c;
  p.d1 = p.d2 = s.d;
  p.fidelity = s.fidelity;
  CorrectedVertical m{GyroVertical(p), {}};
  m.law.H = s.H;
  m.law.f1 = m.law.f2 = s.f;
  m.law.torque_limit_Nm = 1e3;
  return m;
}

GyroVertical::State run(CorrectedVertical& m, GyroVertical::State x, double T, double h) {
  dynamics::Rk4<CorrectedVertical> integ(m);
  const long n = std::lround(T / h);
  for (long k = 0; k < n; ++k) integ.step(static_cast<double>(k) * h, h, x);
  return x;
}

C z_G(double delta, double wP, double omega, double alpha_L) {  // (12.47)
  const double den = delta * delta + (omega + wP) * (omega + wP);
  return C(delta * delta + wP * (omega + wP), -delta * omega) / den * alpha_L;
}

TEST(GyroVerticalOracle, SteadyTurnTrajectoryAndEquilibrium12_46_12_47) {
  const Case s;
  const double delta = s.f / s.H, wP = s.c / s.H, alpha_L = 0.1;
  for (const double omega : {0.03, -0.012, 0.0}) {
    CorrectedVertical m = make(s);
    m.plant.inputs.frame.hold(turn_frame(omega, alpha_L));
    const C zg = z_G(delta, wP, omega, alpha_L);
    GyroVertical::State x = GyroVertical::make_state(0, 0);
    double t = 0;
    for (const double T : {10.0, 40.0, 100.0}) {  // (12.46) steady turn from z = 0
      x = run(m, x, T - t, 0.05);
      t = T;
      const C z = zg * (1.0 - std::exp(-C(delta, omega + wP) * t));
      EXPECT_NEAR(x[0], z.real(), 1e-9 * alpha_L) << "omega " << omega << " t " << t;
      EXPECT_NEAR(x[1], z.imag(), 1e-9 * alpha_L) << "omega " << omega << " t " << t;
    }
    x = run(m, x, 20.0 / delta - t, 0.05);  // e^-20 of the transient left
    std::printf("omega %+.3f: z %.9f%+.9fi  z_G (12.47) %.9f%+.9fi\n", omega, x[0], x[1], zg.real(), zg.imag());
    EXPECT_NEAR(x[0], zg.real(), 1e-8 * alpha_L);
    EXPECT_NEAR(x[1], zg.imag(), 1e-8 * alpha_L);
    if (omega != 0.0) {
      EXPECT_GT(std::fabs(x[1]), 0.1 * alpha_L);  // displaced in β although β_L = 0
    }
  }
}

TEST(GyroVerticalOracle, ResonanceAtMinusOmegaP) {
  Case s;
  s.f = 1e-3;  // δ = 0.002 /s, small against ω^P = 0.005 /s: a sharp resonance
  const double delta = s.f / s.H, wP = s.c / s.H, alpha_L = 0.05;
  double best_omega = 0, best = 0;
  for (int k = -4; k <= 4; ++k) {
    const double omega = -wP + 0.25 * delta * k;
    CorrectedVertical m = make(s);
    m.plant.inputs.frame.hold(turn_frame(omega, alpha_L));
    const GyroVertical::State x = run(m, GyroVertical::make_state(0, 0), 20.0 / delta, 0.5);
    const double mag = std::hypot(x[0], x[1]);
    EXPECT_NEAR(mag, std::abs(z_G(delta, wP, omega, alpha_L)), 1e-7 * alpha_L) << omega;
    if (mag > best) {
      best = mag;
      best_omega = omega;
    }
  }
  std::printf("peak |z|/alpha_L = %.6f at omega = %.6f (book: %.6f at %.6f)\n", best / alpha_L, best_omega,
              std::hypot(delta, wP) / delta, -wP);
  EXPECT_DOUBLE_EQ(best_omega, -wP);
  EXPECT_NEAR(best / alpha_L, std::hypot(delta, wP) / delta, 1e-6);
  // δ = 0: (12.48) has no equilibrium at ω = −ω^P; z' = iω^P α_L, the error grows without bound.
  s.f = 0.0;
  CorrectedVertical m = make(s);
  m.plant.inputs.frame.hold(turn_frame(-wP, alpha_L));
  const GyroVertical::State x = run(m, GyroVertical::make_state(0, 0), 200.0, 0.5);
  EXPECT_NEAR(x[0], 0.0, 1e-12);
  EXPECT_NEAR(x[1], wP * alpha_L * 200.0, 1e-9);
}

TEST(GyroVerticalOracle, UndampedAndAstaticLimits12_48_12_49) {
  const double alpha_L = 0.08;
  {  // δ = 0: precession circle about z_G = ω^P α_L/(ω + ω^P); its mean over a period is z_G
    Case s;
    s.f = 0.0;
    const double wP = s.c / s.H, omega = 0.02, W = omega + wP;
    CorrectedVertical m = make(s);
    m.plant.inputs.frame.hold(turn_frame(omega, alpha_L));
    const double T = 2.0 * 3.14159265358979323846 / W;
    GyroVertical::State x = GyroVertical::make_state(0, 0);
    dynamics::Rk4<CorrectedVertical> integ(m);
    const int n = 4000;
    double sa = 0, sb = 0;
    for (int k = 0; k < n; ++k) {
      integ.step(k * T / n, T / n, x);
      sa += x[0];
      sb += x[1];
    }
    EXPECT_NEAR(sa / n, wP * alpha_L / W, 1e-6 * alpha_L);  // rectangle rule over a period: exact to ~1/n²·0
    EXPECT_NEAR(sb / n, 0.0, 1e-6 * alpha_L);
    EXPECT_LT(wP * alpha_L / W, alpha_L);  // ω > 0: α_G < α_L (book)
  }
  {  // astatic (ω^P = 0), slow correction against the turn: z_G ≈ −i δ α_L/ω
    Case s;
    s.c = 0.0;
    s.f = 5e-4;  // δ = 1e-3, ω = 0.05: δ << ω
    const double delta = s.f / s.H, omega = 0.05;
    CorrectedVertical m = make(s);
    m.plant.inputs.frame.hold(turn_frame(omega, alpha_L));
    const GyroVertical::State x = run(m, GyroVertical::make_state(0, 0), 25.0 / delta, 0.5);
    const C zg = C(delta * delta, -delta * omega) / (delta * delta + omega * omega) * alpha_L;  // (12.49)
    EXPECT_NEAR(x[0], zg.real(), 1e-8 * alpha_L);
    EXPECT_NEAR(x[1], zg.imag(), 1e-8 * alpha_L);
    EXPECT_NEAR(x[1], -delta * alpha_L / omega, 1e-3 * delta * alpha_L / omega);  // the book's approximation
  }
}

TEST(GyroVerticalOracle, DecelerationPulse12_41_12_42) {
  const Case s;
  const double delta = s.f / s.H, wP = s.c / s.H, a = -2.0;
  const double beta_L = std::atan(-a / kG);  // (12.36)
  CorrectedVertical m = make(s);
  m.plant.inputs.frame.hold(straight_frame(a));
  GyroVertical::State x = GyroVertical::make_state(0, 0);
  double t = 0;
  for (const double T : {5.0, 30.0, 60.0}) {
    x = run(m, x, T - t, 0.05);
    t = T;
    const C z = C(0, beta_L) * (1.0 - std::exp(-C(delta, wP) * t));  // (12.42)
    EXPECT_NEAR(x[0], z.real(), 1e-9 * beta_L) << t;
    EXPECT_NEAR(x[1], z.imag(), 1e-9 * beta_L) << t;
  }
  // After the pulse (T = 60 s) the instrument re-erects from z(T) toward the true vertical.
  m.plant.inputs.frame.hold(straight_frame(0.0));
  const C zT(x[0], x[1]);
  x = run(m, x, 50.0, 0.05);
  const C z = zT * std::exp(-C(delta, wP) * 50.0);
  EXPECT_NEAR(x[0], z.real(), 1e-9 * beta_L);
  EXPECT_NEAR(x[1], z.imag(), 1e-9 * beta_L);
}

TEST(GyroVerticalOracle, LinearCorrectionDecayPairingIsTheCorrectedOne) {
  Case s;
  s.c = 0.0;
  CorrectedVertical m = make(s);
  m.law.f1 = 0.01;  // acts on β
  m.law.f2 = 0.03;  // acts on α
  m.plant.inputs.frame.hold(straight_frame(0.0));
  const double a0 = 0.02, b0 = -0.01, T = 40.0;
  const GyroVertical::State x = run(m, GyroVertical::make_state(a0, b0), T, 0.05);
  EXPECT_NEAR(x[0], a0 * std::exp(-m.law.f2 * T / s.H), 1e-11);  // α ∝ e^(−f2 t/H)
  EXPECT_NEAR(x[1], b0 * std::exp(-m.law.f1 * T / s.H), 1e-11);  // β ∝ e^(−f1 t/H)
  // The pairing printed in the book (α ∝ e^(−f1 t/H)) is off by far more than the tolerance here.
  EXPECT_GT(std::fabs(x[0] - a0 * std::exp(-m.law.f1 * T / s.H)), 1e-3);
}

TEST(GyroVerticalOracle, CoulombRowStopsInItsDeadZone) {
  // Rows 3 + 4, precession-level behaviour (Fig. 12.12): the point cannot move while |f e| < r on the other
  // axis, so it ends inside the box |α| ≤ r2/f2, |β| ≤ r1/f1 — not at the origin. Full form (the Coulomb
  // torque needs the rates), sampled law at 1 kHz like the firmware.
  GyroVerticalParams p;
  p.gyro = {2e-3, 2e-3, 0.5};
  p.c = 0.0;
  p.d1 = p.d2 = 2e-3;  // a little bearing damping so that the nutation of the relay-like law decays
  GyroVertical g(p);
  g.inputs.frame.hold(straight_frame(0.0));
  firmware::GyroVerticalCorrectionParams law;
  law.H = 0.5;
  law.f1 = law.f2 = 0.02;
  law.r1 = law.r2 = 4e-4;  // dead zone r/f = 0.02 rad
  law.rate_deadband = 1e-6;
  law.torque_limit_Nm = 1.0;
  GyroVertical::State x = GyroVertical::make_state(0.15, -0.1);
  dynamics::Rk4<GyroVertical> integ(g);
  const double T = 1e-3;
  for (int k = 0; k < 300000; ++k) {
    firmware::CorrectionSignals s;
    g.erection_signal(k * T, x, s.e1, s.e2);
    s.alpha_rate = x[2];
    s.beta_rate = x[3];
    const firmware::CorrectionTorques m = firmware::gyro_vertical_correction(law, s);
    g.inputs.M1 = m.M1;
    g.inputs.M2 = m.M2;
    for (int j = 0; j < 4; ++j) integ.step(k * T + j * T / 4, T / 4, x);
  }
  std::printf("Coulomb: final alpha %.5f beta %.5f (dead zone +-%.3f)\n", x[0], x[1], law.r2 / law.f2);
  EXPECT_LE(std::fabs(x[0]), law.r2 / law.f2 * 1.05);
  EXPECT_LE(std::fabs(x[1]), law.r1 / law.f1 * 1.05);
  EXPECT_GT(std::hypot(x[0], x[1]), 0.2 * law.r1 / law.f1);  // stuck off the origin
}

TEST(GyroVerticalOracle, RelayCorrectionChattersIntoTheOrigin) {
  // Row 5 (Fig. 12.13): straight lines to an axis, then vibration sliding along it into the origin; sampled
  // at T = 1 ms the chatter is ≲ (g/H) T per tick.
  Case s;
  s.c = 0.0;
  CorrectedVertical m = make(s);
  m.law.f1 = m.law.f2 = 0.0;
  m.plant.inputs.frame.hold(straight_frame(0.0));
  GyroVertical g = m.plant;
  firmware::GyroVerticalCorrectionParams law = m.law;
  law.g1 = law.g2 = 2e-3;  // relay rate g/H = 4e-3 rad/s
  GyroVertical::State x = GyroVertical::make_state(0.05, 0.02);
  dynamics::Rk4<GyroVertical> integ(g);
  const double T = 1e-3;
  for (int k = 0; k < 40000; ++k) {
    firmware::CorrectionSignals sg;
    g.erection_signal(k * T, x, sg.e1, sg.e2);
    const firmware::CorrectionTorques t = firmware::gyro_vertical_correction(law, sg);
    g.inputs.M1 = t.M1;
    g.inputs.M2 = t.M2;
    integ.step(k * T, T, x);
  }
  const double chatter = law.g1 / s.H * T;
  std::printf("relay: final |z| %.3e (chatter bound %.3e)\n", std::hypot(x[0], x[1]), 2 * chatter);
  EXPECT_LE(std::hypot(x[0], x[1]), 2.0 * chatter);
}

TEST(GyroVerticalOracle, FullFormWithoutBearingDampingHasAGrowingNutation) {
  // [derived] in the model header: A z'' + (d − iH) z' + (Hω + c − i f) z = 0; at d = 0 the nutation root's
  // real part is ≈ +δ. Measured: the growth of the nutation amplitude |z'| (the precession rate is ~δ|z| and
  // decays) between 100 s and 200 s, against the root of the quadratic.
  Case s;
  s.fidelity = models::InstrumentFidelity::kFull;
  const double A = 2e-3, alpha_L = 0.0, omega = 0.0;
  for (const double d : {0.0, 1e-3}) {
    s.d = d;
    CorrectedVertical m = make(s);
    m.plant.inputs.frame.hold(turn_frame(omega, alpha_L));
    const C b(d, -s.H), cc(s.H * omega + s.c, -s.f);
    const C disc = std::sqrt(b * b - 4.0 * A * cc);
    const C r1 = (-b + disc) / (2.0 * A), r2 = (-b - disc) / (2.0 * A);
    const double nutation_re = std::abs(r1) > std::abs(r2) ? r1.real() : r2.real();
    // Start with a nutation of 1e-6 rad/s in α'. Undamped: measure over [100, 200] s; damped (≈ 0.48 /s):
    // over [1, 6] s, before it sinks below the precession rates.
    const double t1 = d == 0.0 ? 100.0 : 1.0, t2 = d == 0.0 ? 200.0 : 6.0;
    GyroVertical::State x = GyroVertical::make_state(0, 0, 1e-6, 0);
    x = run(m, x, t1, 2.5e-4);
    const double a1 = std::hypot(x[2], x[3]);
    x = run(m, x, t2 - t1, 2.5e-4);
    const double a2 = std::hypot(x[2], x[3]);
    const double growth = std::log(a2 / a1) / (t2 - t1);
    std::printf("d = %g: nutation growth %.6f /s (root %.6f, approx delta - d/A = %.6f)\n", d, growth, nutation_re,
                s.f / s.H - d / A);
    // |z'| on the nutation is ω^N × amplitude; the precession's part δ|z| is below 1e-3 of it, and |z'| of the
    // damped nutation beats slightly with the precession mode's rate: tolerance 1e-3 relative (+1e-5 /s).
    EXPECT_NEAR(growth, nutation_re, 1e-3 * std::fabs(nutation_re) + 1e-5);
    if (d == 0.0) {
      EXPECT_NEAR(nutation_re, s.f / s.H, 1e-3 * s.f / s.H);
      EXPECT_GT(growth, 0.0);
    } else {
      EXPECT_LT(growth, 0.0);
    }
  }
}

TEST(GyroVerticalOracle, FullFormSettlesOnThePrecessionEquilibrium) {
  Case s;
  s.fidelity = models::InstrumentFidelity::kFull;
  s.d = 1e-3;  // bearing damping: stable nutation (previous test); the equilibrium has no rate terms
  const double delta = s.f / s.H, wP = s.c / s.H, alpha_L = 0.1, omega = 0.03;
  CorrectedVertical m = make(s);
  m.plant.inputs.frame.hold(turn_frame(omega, alpha_L));
  // h = 0.25 ms: nutation 250 rad/s at h ω = 0.06.
  const GyroVertical::State x = run(m, GyroVertical::make_state(0, 0), 20.0 / delta, 2.5e-4);
  const C zg = z_G(delta, wP, omega, alpha_L);
  std::printf("full form: z %.7f%+.7fi, z_G %.7f%+.7fi\n", x[0], x[1], zg.real(), zg.imag());
  EXPECT_NEAR(x[0], zg.real(), 2e-5);
  EXPECT_NEAR(x[1], zg.imag(), 2e-5);
}

}  // namespace gyro_vertical_test
}  // namespace gyrostab
