// Oracle tests of the gyrocompass (sim/models/gyrocompass.hpp) with the firmware law
// (firmware/control/gyrocompass_law.hpp) against Magnus ch. 13 (docs/models/gyrocompass.md):
//   fixed base — the trajectory of the precession form against the exact solution of the linear system
//   (13.10), the equilibrium (13.11), the period 2π/ω^K and the decay δ/2 of (13.12) measured from the
//   extrema; the full form's slow mode against its own linearization and the book's (13.12)/(13.16);
//   moving base — the speed deviation (13.23) (20 kn north at 50°: 1.97°), zero ballistic deviation of the
//   Schuler-tuned compass (13.26) during and after a northward acceleration, and the predicted swing
//   |K Δv sinc(ωT/2)|, K = ω^c/g − 1/(R ω^E cosφ), when mistuned (0.5× and 2×: reference 0.96° and 1.92°);
//   rolling error (13.38) on an intercardinal course, and none on a cardinal one.
// The law is evaluated inside the derivative (continuous, the book's setting).
// Steps and tolerances: the precession modes are ≈ 1.2e-3 /s; RK4 at h = 1 s errs by ~(hλ)^5/120 ≈ 2e-17
// per step — tolerances 1e-9 rad on trajectories. Extrema sampled every 1 s and located by a parabola: the
// peak-time error for a sinusoid is O((ωh)² h) ≈ 1e-6 s per extremum, so over ~10 half-periods of 2650 s the
// period is good to 1e-8 relative; the decay rate from three extrema to ~1e-6 relative — tolerance 1e-5.
#include "sim/models/gyrocompass.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "firmware/control/gyrocompass_law.hpp"
#include "sim/analysis/extrema_meter.hpp"
#include "sim/analysis/zero_crossing_meter.hpp"
#include "sim/dynamics/rk4.hpp"
#include "sim/dynamics/eigenvalues.hpp"

namespace gyrostab {
namespace gyrocompass_test {

using models::Gyrocompass;
using models::GyrocompassParams;
constexpr double kPi = std::numbers::pi;
constexpr double kWe = 7.292115e-5, kR = 6.371e6, kG = 9.81;
constexpr double kLat = 50.0 * kPi / 180.0;

struct CorrectedCompass {
  static constexpr int kStateSize = 6;
  using State = Gyrocompass::State;
  mutable Gyrocompass plant;
  firmware::GyrocompassLawParams law;
  // Optional time-varying north speed v_N(t) (ramp from 0 over [0, ramp_T] to dv), else constant v_N.
  double v_north{0.0}, dv{0.0}, ramp_T{0.0};

  // The acceleration jumps at the ramp's ends; every RK4 stage of a step takes it from the step's start
  // (step_t0, set by the caller), so a step ending on a corner sees the left limit (sim/motion/
  // earth_vehicle.hpp: otherwise RK4 errs by O(h Δa)).
  mutable double step_t0{0.0};
  double speed(double t) const {
    if (ramp_T <= 0.0) return v_north;
    return v_north + dv * std::clamp(t / ramp_T, 0.0, 1.0);
  }
  double accel(double) const { return (ramp_T > 0.0 && step_t0 >= 0.0 && step_t0 < ramp_T) ? dv / ramp_T : 0.0; }
  models::FrameSample frame(double t) const {  // (13.20) with v^E = 0, φ fixed; level: f_N = b^N
    return {dynamics::Vec3(kWe * std::sin(kLat), -speed(t) / kR, kWe * std::cos(kLat)), dynamics::Vec3::Zero(),
            dynamics::Vec3(kG, 0.0, accel(t))};
  }
  void derivative(double t, const State& x, State& dx) const {
    plant.inputs.frame.hold(frame(t));
    const firmware::GyrocompassTorques m = firmware::gyrocompass_torques(law, plant.level_signal(t, x));
    plant.inputs.M1 = m.M1;
    plant.inputs.M2 = m.M2;
    plant.derivative(t, x, dx);
  }
  void project(State&) const {}
};

CorrectedCompass make(double c_over_H, double zeta, models::InstrumentFidelity fid) {
  GyrocompassParams p;
  p.gyro = {0.05, 0.05, 2.0};
  p.c = c_over_H * p.gyro.H;
  p.fidelity = fid;
  CorrectedCompass m{Gyrocompass(p), {}};
  m.law.H = p.gyro.H;
  m.law.f = firmware::gyrocompass_damping_for_ratio(p.gyro.H, p.c, kLat, zeta, kWe);
  m.law.torque_limit_Nm = 1e3;
  return m;
}

double tuned_wc() { return models::schuler_tuned_omega_c(kLat, kG, kR, kWe); }

TEST(GyrocompassOracle, TuningNumbersOfTheDigest) {
  // (13.26): c/H = 0.02112 (equator), 0.02438 (30°), 0.03285 (50°), 0.04223 (60°), 0.06174 (70°).
  const double lat[] = {0, 30, 50, 60, 70}, expect[] = {0.02112, 0.02438, 0.03285, 0.04223, 0.06174};
  for (int i = 0; i < 5; ++i) {
    const double phi = lat[i] * kPi / 180.0;
    EXPECT_NEAR(models::schuler_tuned_omega_c(phi, kG, kR, kWe), expect[i], 5e-6) << lat[i];
    EXPECT_DOUBLE_EQ(firmware::schuler_tuned_pendulosity(1.0, phi, kG, kR, kWe),
                     models::schuler_tuned_omega_c(phi, kG, kR, kWe));
    // (13.27): tuned ⇔ T_K (undamped, ω^c >> ω^E) = 2π sqrt(R/g) = 84.39 min
    const double wh = kWe * std::cos(phi);
    EXPECT_NEAR(2 * kPi / std::sqrt(models::schuler_tuned_omega_c(phi, kG, kR, kWe) * wh) / 60.0, 84.39, 0.01);
  }
}

TEST(GyrocompassOracle, FixedBaseTrajectoryEquilibriumPeriodAndDecay13_10_13_12) {
  CorrectedCompass m = make(tuned_wc(), 0.3, models::InstrumentFidelity::kPrecession);
  const models::GyrocompassTheory th{2.0, m.plant.params().c, m.law.f, kWe, kLat};
  // The linear system (13.10): x = (α, β), x' = M x + b.
  const double wh = kWe * std::cos(kLat), delta = th.delta(), wc = th.omega_c();
  Eigen::Matrix2d M;
  M << 0.0, wc + wh, -wh, -delta;
  const Eigen::Vector2d xeq(th.alpha0(), th.beta0());
  const double sigma = 0.5 * M.trace(), w = std::sqrt(M.determinant() - sigma * sigma);
  const Eigen::Vector2d x0(5.0 * kPi / 180.0, 0.0);
  dynamics::Rk4<CorrectedCompass> integ(m);
  Gyrocompass::State x = Gyrocompass::make_state(x0[0], x0[1]);
  analysis::ExtremaMeter<64> ext;
  const double h = 1.0;
  const int n = 40000;
  double err = 0.0;
  for (int k = 0; k < n; ++k) {
    integ.step(k * h, h, x);
    const double t = (k + 1) * h;
    const Eigen::Matrix2d E = std::exp(sigma * t) * (std::cos(w * t) * Eigen::Matrix2d::Identity() +
                                                    std::sin(w * t) / w * (M - sigma * Eigen::Matrix2d::Identity()));
    const Eigen::Vector2d exact = xeq + E * (x0 - xeq);
    err = std::max(err, std::max(std::fabs(x[0] - exact[0]), std::fabs(x[1] - exact[1])));
    ext.add(t, x[0]);
  }
  std::printf("max |x - exact| %.3e rad; alpha0 %.6f deg (book %.6f), beta0 %.6f deg (book %.6f)\n", err,
              x[0] * 180 / kPi, th.alpha0() * 180 / kPi, x[1] * 180 / kPi, th.beta0() * 180 / kPi);
  EXPECT_LT(err, 1e-9);
  // (13.11) after 40000 s: the transient is e^(−δ/2 · 4e4) = e^-14.9 ≈ 3e-7 of 5°: use Aitken on extrema.
  ASSERT_GE(ext.count(), 6);
  EXPECT_NEAR(ext.equilibrium(0), th.alpha0(), 1e-7 * std::fabs(th.alpha0()) + 1e-9);
  EXPECT_NEAR(th.alpha0() * 180 / kPi, -1.55, 0.005);  // reference compass [constructed], Magnus §13.2
  EXPECT_NEAR(th.beta0(), 1.698e-3, 1e-6);
  EXPECT_NEAR(x[1], th.beta0(), 1e-6 * th.beta0());
  // (13.12): period and decay.
  const double T_meas = ext.period(), sigma_meas = ext.decay_rate(0);
  std::printf("period %.4f s (book %.4f s = %.2f min), decay %.6e /s (book %.6e)\n", T_meas, th.period(),
              th.period() / 60, sigma_meas, th.decay_rate());
  EXPECT_NEAR(T_meas / th.period(), 1.0, 1e-5);
  EXPECT_NEAR(sigma_meas / th.decay_rate(), 1.0, 1e-5);
}

TEST(GyrocompassOracle, FullFormSlowModeAgainstTheBook13_12_13_16) {
  // Undamped, full form (13.7): the slow (compass) mode from the simulation, from the 4x4 linearization
  // of the model (exact oracle for the model), and the book's precession (13.12) and strong-coupling (13.16)
  // approximations, which differ from it by O(A c/H²) = 8e-4 and O(ω^E cosφ/ω^c) = 1.4e-3 respectively.
  CorrectedCompass m = make(tuned_wc(), 0.0, models::InstrumentFidelity::kFull);
  const double H = 2.0, A = 0.05, c = m.plant.params().c, wh = kWe * std::cos(kLat);
  Eigen::Matrix4d J;  // x = (α, β, α', β'), (10.22) with Ω = (ω^E sinφ, 0, ω^E cosφ), M2 = −cβ
  J << 0, 0, 1, 0, 0, 0, 0, 1, -H * wh / A, 0, 0, -H / A, 0, -(H * wh + c) / A, H / A, 0;
  const dynamics::EigenvaluesOf<4> ev = dynamics::eigenvalues<4>(J);
  double w_slow = 1e9;
  for (int i = 0; i < 4; ++i) w_slow = std::min(w_slow, std::fabs(ev[i].imag()));
  const double T_lin = 2 * kPi / w_slow;
  dynamics::Rk4<CorrectedCompass> integ(m);
  Gyrocompass::State x = Gyrocompass::make_state(0.05, 0.0);
  analysis::ZeroCrossingMeter zc;  // about α = 0 (undamped: the equilibrium); the slope there is maximal
  const double h = 2.5e-3;  // nutation H/A = 40 rad/s at h ω = 0.1
  const long n = std::lround(12000.0 / h);
  for (long k = 0; k < n; ++k) {
    integ.step(static_cast<double>(k) * h, h, x);
    if ((k + 1) % 400 == 0) zc.add(static_cast<double>(k + 1) * h, x[0]);
  }
  const double T_sim = 2 * kPi / zc.angular_frequency();
  const models::GyrocompassTheory th{H, c, 0.0, kWe, kLat};
  const double T_13_16 = 2 * kPi * std::sqrt((A + H * H / c) / (H * wh));
  std::printf("full form: period %.3f s, linearization %.3f s, (13.12) %.3f s, (13.16) %.3f s\n", T_sim,
              T_lin, th.period(), T_13_16);
  ASSERT_GE(zc.crossings(), 2);
  // The nutation riding on α (amplitude ≈ (precession rate)/ω^N ≈ 6e-8 rad) moves a crossing by ≲ 6e-8 /
  // (α0 ω_K) ≈ 1e-3 s per crossing, 2e-7 of a period; interpolation at the inflection errs by O(h³ ω³):
  // tolerance 3e-6 relative (measured 8e-7).
  EXPECT_NEAR(T_sim / T_lin, 1.0, 3e-6);
  EXPECT_NEAR(T_lin / th.period(), 1.0, 2e-3);
  EXPECT_NEAR(T_lin / T_13_16, 1.0, 2e-3);
  EXPECT_NE(T_lin, th.period());  // the inertia terms are really there
}

TEST(GyrocompassOracle, FullFormDampedNeedsSphereDampingForItsNutation) {
  // [derived] (model header): with f > 0 and d1 = d2 = 0 the quartic has no λ³ term, the roots sum to 0 and
  // the nutation grows at δ/2; with the float's damping d it decays. Measured from |(α', β')| after the
  // precession has settled out of the rates (the precession rates are ~1e-7 rad/s, the nutation 1e-5).
  const double A = 0.05, H = 2.0;
  for (const double d : {0.0, 0.01}) {
    CorrectedCompass m = make(tuned_wc(), 0.3, models::InstrumentFidelity::kFull);
    GyrocompassParams p = m.plant.params();
    p.d1 = p.d2 = d;
    m.plant = Gyrocompass(p);
    const double wh = kWe * std::cos(kLat), c = p.c, f = m.law.f;
    Eigen::Matrix4d J;
    J << 0, 0, 1, 0, 0, 0, 0, 1, -H * wh / A, -f / A, -d / A, -H / A, 0, -(H * wh + c) / A, H / A, -d / A;
    const dynamics::EigenvaluesOf<4> ev = dynamics::eigenvalues<4>(J);
    double nut = 0, nut_mag = 0;
    for (int i = 0; i < 4; ++i) {
      if (std::abs(ev[i]) > nut_mag) {
        nut_mag = std::abs(ev[i]);
        nut = ev[i].real();
      }
    }
    const models::GyrocompassTheory th{H, c, f, kWe, kLat};
    Gyrocompass::State x = Gyrocompass::make_state(th.alpha0(), th.beta0());
    x[2] = 1e-5;
    dynamics::Rk4<CorrectedCompass> integ(m);
    const double h = 2.5e-3;
    auto run_for = [&](double T, double t0) {
      const long n = std::lround(T / h);
      for (long k = 0; k < n; ++k) integ.step(t0 + static_cast<double>(k) * h, h, x);
    };
    // Undamped nutation: over [200, 1000] s; damped (0.2 /s): over [1, 11] s, before it sinks below the
    // precession rates (~1e-10 rad/s from the equilibrium start).
    const double t1 = d == 0.0 ? 200.0 : 1.0, t2 = d == 0.0 ? 1000.0 : 11.0;
    run_for(t1, 0.0);
    const double a1 = std::hypot(x[2], x[3]);
    run_for(t2 - t1, t1);
    const double a2 = std::hypot(x[2], x[3]);
    const double growth = std::log(a2 / a1) / (t2 - t1);
    std::printf("d = %g: nutation growth %.4e /s (linearization %.4e, delta/2 = %.4e)\n", d, growth, nut,
                th.decay_rate());
    if (d == 0.0) {
      EXPECT_NEAR(growth / nut, 1.0, 2e-2);  // the precession part of |x'| is ≲ 1e-7/1e-5 of it
      EXPECT_NEAR(nut / th.decay_rate(), 1.0, 1e-2);
    } else {
      EXPECT_LT(nut, 0.0);
      EXPECT_NEAR(growth / nut, 1.0, 2e-2);  // |x'| of a nutation (two close modes) beats a little: 2 %
    }
  }
}

TEST(GyrocompassOracle, SpeedDeviation13_23) {
  // 20 kn due north at 50°: (13.18) ψ^F = −1.97°, i.e. α0 = −tanψ^F = v^N/(R ω^E cosφ) (13.23).
  const double v = 20.0 * 1852.0 / 3600.0;
  double alpha[2];
  for (int i = 0; i < 2; ++i) {
    CorrectedCompass m = make(tuned_wc(), 0.7, models::InstrumentFidelity::kPrecession);
    m.v_north = i == 0 ? 0.0 : v;
    dynamics::Rk4<CorrectedCompass> integ(m);
    Gyrocompass::State x = Gyrocompass::make_state(0, 0);
    for (int k = 0; k < 40000; ++k) integ.step(k * 1.0, 1.0, x);  // e^-35 of the transient
    alpha[i] = x[0];
  }
  const double book = models::speed_deviation(v, 0.0, kLat, kR, kWe);
  std::printf("speed deviation %.6f deg (book %.6f deg)\n", (alpha[1] - alpha[0]) * 180 / kPi, book * 180 / kPi);
  EXPECT_NEAR(alpha[1] - alpha[0], book, 1e-9);
  EXPECT_NEAR(std::atan(book) * 180 / kPi, 1.97, 0.005);
}

// The level sensor reads the exact apparent tilt atan(b/g), the book b/g: the tuned compass therefore
// lags the speed deviation by ω^c ((b/g) − atan(b/g)) T_ramp after the ramp (third order: 3.2e-6 rad here).
double level_nonlinearity_residual(double wc, double dv, double ramp_T) {
  const double x = dv / ramp_T / kG;
  return wc * (x - std::atan(x)) * ramp_T;
}

double ballistic_swing(double wc_factor, double* predicted) {
  // 0 → 10 m/s north in 60 s at 50°, undamped, started on the equilibrium of v = 0; max |α − α_eq(t)|.
  CorrectedCompass m = make(wc_factor * tuned_wc(), 0.0, models::InstrumentFidelity::kPrecession);
  m.dv = 10.0;
  m.ramp_T = 60.0;
  const double wh = kWe * std::cos(kLat), wc = m.plant.params().c / 2.0;
  dynamics::Rk4<CorrectedCompass> integ(m);
  Gyrocompass::State x = Gyrocompass::make_state(0.0, kWe * std::sin(kLat) / (wc + wh));
  double dev = 0.0;
  for (int k = 0; k < 20000; ++k) {
    m.step_t0 = k * 1.0;
    integ.step(k * 1.0, 1.0, x);
    const double t = k + 1.0;
    dev = std::max(dev, std::fabs(x[0] - m.speed(t) / (kR * wh)));
  }
  const double w = std::sqrt(wh * (wc + wh)), K = wc / kG - 1.0 / (kR * wh), arg = 0.5 * w * m.ramp_T;
  *predicted = std::fabs(K * m.dv * std::sin(arg) / arg);
  return dev;
}

TEST(GyrocompassOracle, NoBallisticDeviationWhenSchulerTuned13_26) {
  double pred;
  const double tuned = ballistic_swing(1.0, &pred);
  const double residual = level_nonlinearity_residual(tuned_wc(), 10.0, 60.0);
  std::printf("tuned: max deviation from the speed deviation %.4e rad (book 0, level atan residual %.4e)\n", tuned,
              residual);
  EXPECT_LT(pred, 1e-12);
  // RK4 is exact to rounding on this linear, piecewise-linearly forced system; what remains is the level's
  // third-order nonlinearity, 5e-5 of the 0.0167 rad speed deviation.
  EXPECT_NEAR(tuned / residual, 1.0, 1e-3);
  for (const double factor : {0.5, 2.0}) {
    const double swing = ballistic_swing(factor, &pred);
    std::printf("omega_c x%.1f: swing %.6f deg (predicted %.6f deg)\n", factor, swing * 180 / kPi, pred * 180 / kPi);
    // The peak of a sampled (h = 1 s) 84-min oscillation is low by ≤ 1 − cos(ω h/2) ≈ 2e-7; the level's atan
    // changes the forcing by (b/g)²/3 = 1e-4 relative, acting through K or ω^c: tolerance 5e-4.
    EXPECT_NEAR(swing / pred, 1.0, 5e-4);
  }
  ballistic_swing(0.5, &pred);
  EXPECT_NEAR(pred * 180 / kPi, 0.96, 0.01);  // reference case, Magnus §13.3.2
  ballistic_swing(2.0, &pred);
  EXPECT_NEAR(pred * 180 / kPi, 1.92, 0.01);
}

double rolling_mean_alpha(double psi, double* predicted_exact, double* predicted_book, double* damping_alpha0) {
  CorrectedCompass m = make(tuned_wc(), 0.7, models::InstrumentFidelity::kPrecession);
  GyrocompassParams p = m.plant.params();
  p.roll = {10.0 * kPi / 180.0, 10.0, 10.0};  // Φ 10°, 10 s, h 10 m: b0 = 0.689 m/s²
  const double ws = p.roll.omega(), wg = 0.2 * ws;
  p.swing_inertia = p.c / (wg * wg);
  m.plant = Gyrocompass(p);
  m.plant.inputs.heading = psi;
  const double H = 2.0, wh = kWe * std::cos(kLat), b0 = p.roll.b0(), c = p.c;
  const models::GyrocompassTheory th{H, c, m.law.f, kWe, kLat};
  // Start the swing on its forced solution (13.34) (b = −b0 sin ω_s t) so no free swing is left.
  Gyrocompass::State x = Gyrocompass::make_state(th.alpha0(), th.beta0());
  const double amp = -(b0 / kG) * wg * wg * std::cos(psi + x[0]) / (wg * wg - ws * ws);
  x[5] = amp * ws;
  dynamics::Rk4<CorrectedCompass> integ(m);
  const double h = 0.05;  // 200 steps per roll period
  const long settle = std::lround(20000.0 / h), avg = std::lround(2000.0 / h);  // 200 roll periods averaged
  double sum = 0.0;
  for (long k = 0; k < settle + avg; ++k) {
    integ.step(static_cast<double>(k) * h, h, x);
    if (k >= settle) sum += x[0];
  }
  // Balance H ω^E cosφ (α − α0) = M10(α), M10 = −c b0² ω_γ² sin2(α+ψ)/(4 g² (ω_γ² − ω_s²)) (13.37), solved
  // by fixed-point iteration (exact in α); and the book's linearized (13.38).
  const double k0 = -c * b0 * b0 * wg * wg / (4 * kG * kG * (wg * wg - ws * ws));
  double a = th.alpha0();
  for (int i = 0; i < 50; ++i) a = th.alpha0() + k0 * std::sin(2 * (a + psi)) / (H * wh);
  *predicted_exact = a - th.alpha0();
  *predicted_book = -c * b0 * b0 * wg * wg * std::sin(2 * psi) /
                    (4 * kG * kG * H * wh * (wg * wg - ws * ws) + 2 * c * b0 * b0 * wg * wg * std::cos(2 * psi));
  *damping_alpha0 = th.alpha0();
  return sum / static_cast<double>(avg);
}

TEST(GyrocompassOracle, RollingErrorOnIntercardinalCourses13_38) {
  double exact, book, a0;
  const double mean45 = rolling_mean_alpha(kPi / 4, &exact, &book, &a0);
  std::printf("rolling error at 45 deg: %.6f rad (exact balance %.6f, book (13.38) %.6f, reference 0.0346)\n",
              mean45 - a0, exact, book);
  // Averaging over 200 whole roll periods of a response with a 2ω_s ripple of relative size
  // ω^E cosφ/(2ω_s) ≈ 4e-5, and the transient left after 20000 s (e^(−ζ ω_n t) = e^-17): tolerance 1e-4.
  EXPECT_NEAR((mean45 - a0) / exact, 1.0, 1e-4);
  EXPECT_NEAR(book / exact, 1.0, 1e-2);  // (13.38) linearizes sin 2(α + ψ): O(α²) ≈ 1e-3 here
  // The reference [constructed] 0.0346 rad (docs/models/gyrocompass.md) is the ω_γ << ω_s approximation
  // (13.39): (ω^c/(ω^E cosφ)) (b0/g)² (ω_γ/ω_s)² sin2ψ/4; (13.38) has ω_γ²/(ω_s² − ω_γ²) instead of
  // (ω_γ/ω_s)², 1/0.96 more at ω_γ/ω_s = 0.2.
  const double wh = kWe * std::cos(kLat), b0g = (10.0 * 10.0 * kPi / 180.0 * std::pow(2 * kPi / 10.0, 2)) / kG;
  const double approx_13_39 = tuned_wc() / wh * b0g * b0g * 0.04 / 4.0;
  EXPECT_NEAR(approx_13_39, 0.0346, 5e-5);
  EXPECT_NEAR(std::fabs(book) / approx_13_39, 1.0 / 0.96, 2e-3);  // + the cos2ψ term of (13.38)'s denominator
  const double mean0 = rolling_mean_alpha(0.0, &exact, &book, &a0);
  std::printf("rolling error at 0 deg: %.3e rad\n", mean0 - a0);
  // Cardinal heading: (13.38) gives 0; the model keeps the part from sin 2(α0 + ψ) with the damping error
  // α0 ≠ 0, which the exact balance predicts.
  EXPECT_EQ(book, 0.0);
  EXPECT_NEAR(mean0 - a0, exact, 1e-4 * 0.0346);
  EXPECT_LT(std::fabs(mean0 - a0), 0.2 * 0.0346);
}

}  // namespace gyrocompass_test
}  // namespace gyrostab
