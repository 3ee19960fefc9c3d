// Oracle tests of the directional (heading) gyro (sim/models/directional_gyro.hpp, the plant
// sim/plants/directional_gyro_plant.hpp) with its firmware corrections
// (firmware/control/directional_gyro_corrections.hpp) against Magnus §12.2 (docs/models/directional-gyro.md):
//   (a) apparent drift (12.21)-(12.22) of the uncorrected gyro on an aircraft at 50° flying east at 250 m/s
//       (11.52 °/h Earth rate + 9.65 °/h transport), and its cancellation by the compensating torque (12.22);
//   (b) turn error in a level turn at constant bank φ0: β against β^K + β^P of (12.25) + (12.29), the rotor's
//       azimuth drift δ against (12.32) as corrected (the integral of (12.31)), for c = k/(Hψ'0) from 0.01 to
//       50 and the limits (12.33) c → 0, (12.34) c → ∞; the neglected terms' order shown over two banks;
//   (c) heading correction (12.23): exponential approach of the indication to the reference at κ;
//   the law's start-up check.
// The model is exact in the gimbal kinematics; the book linearizes in the bank (β^K ≈ −φ0 sin ψ, δ' ≈ β^P' φ0
// cos ψ), so (b) differs from the book by the neglected orders, which the tolerances carry (see (b)).
#include "sim/models/directional_gyro.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "firmware/control/directional_gyro_corrections.hpp"
#include "sim/dynamics/rk4.hpp"
#include "sim/plants/directional_gyro_plant.hpp"

namespace gyrostab {
namespace directional_gyro_test {

constexpr double kPi = std::numbers::pi;
constexpr double kDeg = kPi / 180.0;
constexpr double kWe = 7.292115e-5, kR = 6.371e6;
constexpr double kRadSToDegH = 180.0 / kPi * 3600.0;

// ---------------------------------------------------------------------------------------------------------
// (a), (c): the plant on the vehicle, the law sampled once per tick (no latency: the loop's own delay is not
// what these oracles are about).
struct ClosedLoop {
  plants::DirectionalGyroPlant plant;
  firmware::DirectionalGyroCorrectionParams law;
  plants::DirectionalGyroPlant::SensorFrame frame{};
  plants::DirectionalGyroPlant::ActuatorFrame cmd{};
  firmware::DirectionalGyroTorques last{};

  ClosedLoop(const plants::DirectionalGyroPlantParams& p, const plants::PlantTiming& t,
             const firmware::DirectionalGyroCorrectionParams& l)
      : plant(p, t), law(l) {}
  void tick(std::int64_t k) {
    plant.sense(k, frame);
    last = firmware::directional_gyro_corrections(
        law, {frame.indicated_heading_rad, frame.inner_gimbal_rad, frame.compass_heading_rad,
              frame.case_yaw_rate_rad_s});
    cmd.outer_torquer_Nm = last.M1;
    cmd.inner_torquer_Nm = last.M2;
    plant.actuate(cmd);
    plant.advance(k);
  }
};

plants::DirectionalGyroPlantParams eastbound(double speed) {
  plants::DirectionalGyroPlantParams p;
  p.vehicle.start = {.latitude = 50.0 * kDeg, .longitude = 0.0, .heading = 90.0 * kDeg, .speed = speed};
  p.gyro.H = 0.1;
  return p;
}

TEST(DirectionalGyroOracle, DriftNumbers12_21_12_22) {
  // The constructed reference case: 50° latitude, 250 m/s due east.
  const double earth = kWe * std::sin(50.0 * kDeg) * kRadSToDegH;
  const double transport = 250.0 / kR * std::tan(50.0 * kDeg) * kRadSToDegH;
  std::printf("Earth-rate term %.4f deg/h, transport term %.4f deg/h\n", earth, transport);
  EXPECT_NEAR(earth, 11.52, 0.005);
  EXPECT_NEAR(transport, 9.65, 0.005);
  // (12.21): the transport term is the east speed read as an extra Earth rate, ω^F sin φ.
  const double omega_F = 250.0 / (kR * std::cos(50.0 * kDeg));
  EXPECT_NEAR(omega_F * std::sin(50.0 * kDeg) * kRadSToDegH, transport, 1e-12);
  EXPECT_DOUBLE_EQ(firmware::apparent_drift_rate(kWe, kR, 50.0 * kDeg, 250.0, 90.0 * kDeg),
                   -kWe * firmware::math::sin(50.0 * kDeg) -
                       250.0 / kR * firmware::math::sin(50.0 * kDeg) / firmware::math::cos(50.0 * kDeg));
}

// (a) Over 600 s the indicated-minus-true heading changes by ∫(12.22) along the flown path (uncompensated),
// or by ∫[(12.22) − (12.22) at the compensation's φ_c, v_c and the indicated heading] (compensated).
// What the model has and (12.22) has not: the aircraft's bank. Following a great circle over the rotating
// Earth takes a bank φ_b ≈ 2 ω^E sin φ v / g (0.16°: the Coriolis force), so the level frame's horizontal
// rate Ω_h (≈ ω^E cos φ + v/R = 6.6e-5 rad/s) has the component Ω_h sin φ_b along the case's normal axis
// — a heading rate (12.22) does not contain. The tolerance is ∫ Ω_h |sin φ_b| dt (summed from the run's
// samples, 1.1e-4 rad over 600 s) × 1.5, plus 1e-9 rad; the inter-gimbal correction's β ≈ −(H/k)Ω_j couples
// at O(β Ω_fwd) ≈ 0 on this course and RK4 at 10 ms on rates of 1e-4 /s errs by ~1e-20 per step.
// Uncompensated, 21.17 °/h × 600 s = 3.5°: a sign slip in either term errs by ≥ 1.6°, far outside.
struct DriftRun {
  double measured{0.0}, predicted{0.0}, bank_bound{0.0}, book{0.0};
};
DriftRun drift_run(bool compensate) {
  const plants::PlantTiming t{.tick_ns = 10'000'000, .substeps = 1, .seed = 1};
  firmware::DirectionalGyroCorrectionParams law;
  law.H = 0.1;
  law.compensate = compensate;
  law.latitude = 50.0 * kDeg;
  law.speed = 250.0;
  law.k = 0.05 * law.H;  // β settles at k/H = 0.05 /s
  ClosedLoop loop(eastbound(250.0), t, law);
  const double h = t.tick_s();
  const std::int64_t n = 60'000;
  DriftRun r;
  const double e0 = loop.plant.indicated_heading_unwrapped_rad() - loop.plant.true_heading_rad();
  double psi_prev = loop.plant.true_heading_rad(), psi_unwrapped = psi_prev;
  for (std::int64_t k = 0; k < n; ++k) {
    const motion::EarthVehicleSample& m = loop.plant.motion();
    const double book = firmware::apparent_drift_rate(kWe, kR, m.latitude, m.speed, m.heading);
    const double comp = compensate ? -firmware::drift_compensation_torque(law, loop.plant.indicated_heading_rad()) / law.H
                                   : 0.0;
    // Trapezoid over the tick: both ends are samples of the same smooth path.
    const double w_h = std::hypot(m.v_east / kR + kWe * std::cos(m.latitude), m.v_north / kR);
    const double b0 = std::fabs(std::sin(loop.plant.bank_rad()));
    loop.tick(k);
    const motion::EarthVehicleSample& m1 = loop.plant.motion();
    const double book1 = firmware::apparent_drift_rate(kWe, kR, m1.latitude, m1.speed, m1.heading);
    const double comp1 =
        compensate ? -firmware::drift_compensation_torque(law, loop.plant.indicated_heading_rad()) / law.H : 0.0;
    r.book += 0.5 * h * (book + book1);
    r.predicted += 0.5 * h * (book + comp + book1 + comp1);
    r.bank_bound += h * w_h * 0.5 * (b0 + std::fabs(std::sin(loop.plant.bank_rad())));
    psi_unwrapped += std::remainder(loop.plant.true_heading_rad() - psi_prev, 2 * kPi);
    psi_prev = loop.plant.true_heading_rad();
  }
  r.measured = loop.plant.indicated_heading_unwrapped_rad() - psi_unwrapped - e0;
  return r;
}

TEST(DirectionalGyroOracle, ApparentDriftUncompensated12_22) {
  const DriftRun r = drift_run(false);
  const double T = 600.0;
  std::printf("uncompensated: measured %.5f deg/h, (12.22) along the path %.5f deg/h, |diff| %.3e rad, tol %.3e rad\n",
              r.measured / T * kRadSToDegH, r.predicted / T * kRadSToDegH, std::fabs(r.measured - r.predicted),
              1.5 * r.bank_bound + 1e-9);
  EXPECT_NEAR(r.measured, r.predicted, 1.5 * r.bank_bound + 1e-9);
  EXPECT_NEAR(r.predicted / T * kRadSToDegH, -(11.52 + 9.65), 0.05);  // the path stays near 50°, east
  EXPECT_GT(r.bank_bound, 0.0);
}

TEST(DirectionalGyroOracle, ApparentDriftCompensated12_22) {
  const DriftRun r = drift_run(true);
  const double T = 600.0;
  std::printf("compensated: measured %.5f deg/h (uncompensated book %.3f deg/h), predicted residual %.5f deg/h, "
              "|diff| %.3e rad, tol %.3e rad\n",
              r.measured / T * kRadSToDegH, r.book / T * kRadSToDegH, r.predicted / T * kRadSToDegH,
              std::fabs(r.measured - r.predicted), 1.5 * r.bank_bound + 1e-9);
  EXPECT_NEAR(r.measured, r.predicted, 1.5 * r.bank_bound + 1e-9);
  // ≈ 0: under 0.1 °/h (the book's drift of good instruments) against 21.17 °/h uncompensated.
  EXPECT_LT(std::fabs(r.measured / T * kRadSToDegH), 0.1);
  EXPECT_LT(r.book / T * kRadSToDegH, -21.0);
}

// ---------------------------------------------------------------------------------------------------------
// (b) The turn error. The book's setting: a level turn at constant yaw rate ψ'0 and bank φ0, the rotor along
// the flight direction at ψ = 0 (α = β = 0), the inter-gimbal correction M1 = −kβ (continuous: the law is
// evaluated inside the derivative), no other torque, no Earth rate. The case rate is constant in case axes
// (plants::case_rate_of of the track rate (0, 0, −ψ'0) banked by φ0).
struct Turn {
  static constexpr int kStateSize = 2;
  using State = models::DirectionalGyro::State;
  mutable models::DirectionalGyro gyro;
  firmware::DirectionalGyroCorrectionParams law;
  double turn_signal{0.0};  // what the turn-rate sensor reads (the cut-out's input) [rad/s]
  Turn(double H, double k, double bank, double yaw_rate) : gyro(models::DirectionalGyroParams{H}) {
    law.H = H;
    law.compensate = false;
    law.k = k;
    law.torque_limit_Nm = 1e9;
    gyro.inputs.case_rate.hold(plants::case_rate_of(dynamics::Vec3(0.0, 0.0, -yaw_rate), bank, 0.0));
  }
  void derivative(double t, const State& x, State& dx) const {
    const firmware::DirectionalGyroTorques m =
        firmware::directional_gyro_corrections(law, {0.0, x[1], 0.0, turn_signal});
    gyro.inputs.M1 = m.M1;
    gyro.inputs.M2 = m.M2;
    gyro.derivative(t, x, dx);
  }
  void project(State&) const {}
};

// The rotor's azimuth in the level frame that turned by ψ (clockwise from the flight direction at ψ = 0).
double rotor_azimuth(double alpha, double beta, double bank, double psi) {
  const dynamics::Vec3 e = models::directional_gyro_rotor_axis(alpha, beta);
  const double f = e.z(), r = e.y(), d = -e.x();
  const double lr = std::cos(bank) * r - std::sin(bank) * d;
  return std::atan2(std::sin(psi) * f + std::cos(psi) * lr, std::cos(psi) * f - std::sin(psi) * lr);
}

// The book's closed forms in the turned heading ψ (rad).
double beta_P_12_29(double c, double phi0, double psi) {
  return c * phi0 / (c * c + 1) * (std::exp(-c * psi) + c * std::sin(psi) - std::cos(psi));
}
// (12.32) as corrected: the integral of (12.31) from δ(0) = 0. The printed form puts the exponential in
// front of {sin ψ + c(1 − cos ψ)}; the integral has it on the ψ-dependent part only.
double delta_12_32(double c, double phi0, double psi) {
  const double s = std::sin(psi), co = std::cos(psi);
  return c * phi0 * phi0 / (2 * (c * c + 1)) *
         (c * psi + c * s * co + s * s - 2 * c / (c * c + 1) * (std::exp(-c * psi) * (s - c * co) + c));
}
double delta_12_31_rate(double c, double phi0, double psi) {  // dδ/dψ
  const double s = std::sin(psi), co = std::cos(psi);
  return c * phi0 * phi0 / (c * c + 1) * (c * co * co + s * co - c * std::exp(-c * psi) * co);
}
// A bound of |δ| of (12.32) over [0, ψ]: the bracket is ≤ cψ + 1 + 3c.
double delta_scale(double c, double phi0, double psi) {
  return c * phi0 * phi0 / (2 * (c * c + 1)) * (c * psi + 1 + 3 * c);
}

struct TurnErrors {
  double beta{0.0}, delta{0.0};        // max |sim − book| [rad]
  double beta_over_tol{0.0}, delta_over_tol{0.0};  // max |sim − book| / tolerance
  double lim33{0.0}, lim34{0.0};       // max |δ − (12.33)|, |δ − (12.34)| over their tolerance (< 1 passes)
  double delta_end{0.0}, book_end{0.0};
};

// Two full turns (ψ = 0 … 4π) at ψ'0 = 3°/s, H = 0.1 N m s, RK4 at 10 ms: the fastest rate is k/H = cψ'0
// = 2.6 /s at c = 50 (hλ = 0.026, RK4's error (hλ)^5/120 ≈ 1e-10 per step, 1e-6 of the smallest tolerance).
TurnErrors turn_errors(double c, double phi0) {
  const double yaw_rate = 3.0 * kDeg, H = 0.1;
  const Turn turn(H, c * H * yaw_rate, phi0, yaw_rate);
  dynamics::Rk4<Turn> rk4(turn);
  Turn::State x = models::DirectionalGyro::make_state(0.0, 0.0);
  const double h = 0.01;
  const int n = static_cast<int>(std::lround(4 * kPi / yaw_rate / h));
  TurnErrors e;
  const double p2 = phi0 * phi0;
  for (int i = 0; i < n; ++i) {
    rk4.step(i * h, h, x);
    const double psi = (i + 1) * h * yaw_rate;
    const double beta_book = -phi0 * std::sin(psi) + beta_P_12_29(c, phi0, psi);
    const double delta = rotor_azimuth(x[0], x[1], phi0, psi);
    const double delta_book = delta_12_32(c, phi0, psi);
    // Tolerances (model header): the book linearizes in φ0. β = β^K + β^P drops O(φ0³) terms (sin φ0 vs φ0,
    // the products of the bank and β in the gimbal kinematics) and the bank times the azimuth drift δ, which
    // grows as ½φ0²ψ: |Δβ| ≤ φ0³ (1 + ψ/2). δ is O(φ0²) with a relative error O(φ0²): |Δδ| ≤ 2 φ0² × (the
    // bound delta_scale of |δ|). Both orders are confirmed by the scaling over two banks (test below).
    const double tol_beta = phi0 * p2 * (1 + psi / 2), tol_delta = 2 * p2 * delta_scale(c, phi0, psi);
    e.beta = std::max(e.beta, std::fabs(x[1] - beta_book));
    e.delta = std::max(e.delta, std::fabs(delta - delta_book));
    e.beta_over_tol = std::max(e.beta_over_tol, std::fabs(x[1] - beta_book) / tol_beta);
    e.delta_over_tol = std::max(e.delta_over_tol, std::fabs(delta - delta_book) / tol_delta);
    // The limits' own truncation, from expanding (12.32): c → 0, |δ − (12.33)| ≤ c²φ0²(ψ + 4)/2;
    // c → ∞, |δ − (12.34)| ≤ φ0²/(2c) (5 + (ψ + 3)/c).
    const double t33 = c * c * p2 * (psi + 4) / 2 + tol_delta;
    const double t34 = p2 / (2 * c) * (5 + (psi + 3) / c) + tol_delta;
    e.lim33 = std::max(e.lim33, std::fabs(delta - c * p2 / 4 * (1 - std::cos(2 * psi))) / t33);
    e.lim34 = std::max(e.lim34, std::fabs(delta - p2 / 2 * (psi + std::sin(psi) * std::cos(psi))) / t34);
    e.delta_end = delta;
    e.book_end = delta_book;
  }
  return e;
}

TEST(DirectionalGyroOracle, CorrectedClosedForm12_32IsTheIntegralOf12_31) {
  // The closed form used below against a quadrature of (12.31) (Simpson, 4000 panels: its error
  // ψ h⁴ max|f⁗|/180 with f⁗ ~ c⁴ e^(−cψ) stays below 1e-11 for c ≤ 7, ψ ≤ 10; tolerance 1e-10) —
  // and the printed form is not (the reference mismatch at c = 0.5, ψ = 1, φ0 = 0.2: 0.00732 vs 0.00607).
  for (double c : {0.01, 0.5, 1.0, 7.0}) {
    for (double psi_end : {1.0, 3.0, 10.0}) {
      const int m = 4000;
      const double hq = psi_end / m;
      double sum = delta_12_31_rate(c, 0.2, 0.0) + delta_12_31_rate(c, 0.2, psi_end);
      for (int i = 1; i < m; ++i) sum += (i % 2 ? 4.0 : 2.0) * delta_12_31_rate(c, 0.2, i * hq);
      EXPECT_NEAR(delta_12_32(c, 0.2, psi_end), sum * hq / 3, 1e-10) << c << " " << psi_end;
    }
  }
  const double c = 0.5, psi = 1.0, phi0 = 0.2;
  const double printed = c * phi0 * phi0 / (2 * (c * c + 1)) *
                         (c * psi + c * std::sin(psi) * std::cos(psi) + std::sin(psi) * std::sin(psi) -
                          2 * c * std::exp(-c * psi) / (c * c + 1) * (std::sin(psi) + c * (1 - std::cos(psi))));
  EXPECT_NEAR(printed, 0.00732, 5e-6);
  EXPECT_NEAR(delta_12_32(c, phi0, psi), 0.00607, 5e-6);
}

TEST(DirectionalGyroOracle, TurnError12_29_12_32) {
  for (double c : {0.01, 0.3, 1.0, 3.0, 50.0}) {
    for (double phi0 : {0.1, 0.05}) {
      const TurnErrors e = turn_errors(c, phi0);
      std::printf("c %5.2f phi0 %.2f: max|beta - book| %.3e (%.3f phi0^3, %.2f of tol), max|delta - (12.32)| %.3e "
                  "(%.3f phi0^4, %.2f of tol), delta(4pi) %.5e, book %.5e\n",
                  c, phi0, e.beta, e.beta / std::pow(phi0, 3), e.beta_over_tol, e.delta, e.delta / std::pow(phi0, 4),
                  e.delta_over_tol, e.delta_end, e.book_end);
      EXPECT_LT(e.beta_over_tol, 1.0) << c << " " << phi0;
      EXPECT_LT(e.delta_over_tol, 1.0) << c << " " << phi0;
      // The drift is there and has the book's size (not a tolerance that swallows it).
      EXPECT_NEAR(e.delta_end / e.book_end, 1.0, 0.05) << c << " " << phi0;
    }
  }
}

TEST(DirectionalGyroOracle, TurnErrorLimits12_33_12_34) {
  for (double phi0 : {0.1, 0.05}) {
    const TurnErrors weak = turn_errors(0.01, phi0), strong = turn_errors(50.0, phi0);
    std::printf("phi0 %.2f: c = 0.01 vs (12.33) max |diff| / tol %.3f; c = 50 vs (12.34) %.3f\n", phi0, weak.lim33,
                strong.lim34);
    EXPECT_LT(weak.lim33, 1.0);
    EXPECT_LT(strong.lim34, 1.0);
    // (12.34) grows with the heading turned (capture): ½φ0²·4π after two turns; (12.33) stays bounded.
    EXPECT_NEAR(strong.delta_end, 0.5 * phi0 * phi0 * 4 * kPi, 0.03 * 0.5 * phi0 * phi0 * 4 * kPi);
    EXPECT_LT(std::fabs(weak.delta_end), 0.01 * phi0 * phi0);
  }
}

TEST(DirectionalGyroOracle, TurnErrorNeglectedOrdersScaleWithTheBank) {
  // Halving φ0 divides the β error by 8 (φ0³) and the δ error by 16 (φ0⁴ = relative φ0² of an O(φ0²) δ).
  for (double c : {0.3, 1.0, 3.0}) {
    const TurnErrors big = turn_errors(c, 0.1), small = turn_errors(c, 0.05);
    const double rb = big.beta / small.beta, rd = big.delta / small.delta;
    std::printf("c %.1f: beta error ratio %.3f (phi0^3: 8), delta error ratio %.3f (phi0^4: 16)\n", c, rb, rd);
    EXPECT_NEAR(rb, 8.0, 1.0) << c;
    EXPECT_NEAR(rd, 16.0, 2.0) << c;
  }
}

TEST(DirectionalGyroOracle, TurnCutOutLeavesTheFreeGyrosExactKinematics) {
  // The book's remedy: no correction in the turn (c = 0), no turn error. The rotor then stays fixed in space,
  // δ = 0, and the gimbal angles are the exact kinematics of the "321" heading gyro in a level turn:
  // sin β = −sin φ0 sin ψ (so β^K of (12.25) to first order), tan α = tan ψ cos φ0 ((12.13)). At 20° bank over
  // two turns, RK4 at 10 ms on rates ≤ ψ'0 = 0.052 /s: tolerance 1e-9 rad (the integration's error ~1e-12).
  const double yaw_rate = 3.0 * kDeg, H = 0.1, phi0 = 20.0 * kDeg;
  Turn turn(H, 1.0 * H * yaw_rate, phi0, yaw_rate);
  turn.law.turn_cutout_rate = 1.0 * kDeg;
  turn.turn_signal = yaw_rate;
  dynamics::Rk4<Turn> rk4(turn);
  Turn::State x = models::DirectionalGyro::make_state(0.0, 0.0);
  const double h = 0.01;
  double worst_delta = 0.0, worst_beta = 0.0, worst_alpha = 0.0;
  for (int i = 0; i < 24000; ++i) {
    rk4.step(i * h, h, x);
    const double psi = (i + 1) * h * yaw_rate;
    worst_delta = std::max(worst_delta, std::fabs(rotor_azimuth(x[0], x[1], phi0, psi)));
    worst_beta = std::max(worst_beta, std::fabs(x[1] - std::asin(-std::sin(phi0) * std::sin(psi))));
    const double alpha_exact = std::atan2(std::sin(psi) * std::cos(phi0), std::cos(psi));
    worst_alpha = std::max(worst_alpha, std::fabs(std::remainder(x[0] - alpha_exact, 2 * kPi)));
  }
  // The law alone at β = 0.1 in the turn: the cut-out removes M1 and says so.
  const firmware::DirectionalGyroTorques cut =
      firmware::directional_gyro_corrections(turn.law, {0.0, 0.1, 0.0, yaw_rate});
  std::printf("cut out: max |delta| %.3e, max |beta - exact| %.3e, max |alpha - (12.13)| %.3e rad\n", worst_delta,
              worst_beta, worst_alpha);
  EXPECT_TRUE(cut.cut_out);
  EXPECT_EQ(cut.M1, 0.0);
  EXPECT_LT(worst_delta, 1e-9);
  EXPECT_LT(worst_beta, 1e-9);
  EXPECT_LT(worst_alpha, 1e-9);
}

// ---------------------------------------------------------------------------------------------------------
// (c) Heading correction at rest (50°, heading 30°, compensation exact there): the card misset by 5°, the
// compass exact. Sampled at T = 10 ms without latency the error follows e_k = e0 (1 − κT)^k exactly but for
// the inter-gimbal coupling: β settles at ≈ −(H/k)Ω_j with Ω_j ≤ ω^E and couples into α' at β·Ω_fwd ≤ (ω^E)²H/k,
// so |e − e0(1 − κT)^k| ≤ (ω^E)²(H/k) t + 1e-12. Against the book's continuous e0 e^(−κt) the sampling adds
// e0 κt·κT/2 (from k ln(1 − κT) = −κt(1 + κT/2 + …)), tolerance that × 1.2 plus the coupling bound.
TEST(DirectionalGyroOracle, HeadingCorrectionExponential12_23) {
  plants::DirectionalGyroPlantParams p;
  p.vehicle.start = {.latitude = 50.0 * kDeg, .longitude = 0.0, .heading = 30.0 * kDeg, .speed = 0.0};
  p.gyro.H = 0.1;
  p.heading_error0 = 5.0 * kDeg;
  firmware::DirectionalGyroCorrectionParams law;
  law.H = 0.1;
  law.latitude = 50.0 * kDeg;
  law.speed = 0.0;
  law.heading_rate = 2.0 / 60.0;  // 2 °/min at 1° of error
  law.k = 0.05 * law.H;
  const plants::PlantTiming t{.tick_ns = 10'000'000, .substeps = 1, .seed = 1};
  ClosedLoop loop(p, t, law);
  const double T = t.tick_s(), kappa = law.heading_rate, e0 = 5.0 * kDeg;
  const double coupling = kWe * kWe * law.H / law.k;
  double worst_discrete = 0.0, worst_book = 0.0;
  for (std::int64_t k = 0; k < 9000; ++k) {  // 90 s = 3 time constants
    loop.tick(k);
    const double tk = static_cast<double>(k + 1) * T;
    const double e = loop.plant.indicated_heading_unwrapped_rad() - loop.plant.true_heading_rad();
    const double discrete = e0 * std::pow(1 - kappa * T, static_cast<double>(k + 1));
    const double book = e0 * std::exp(-kappa * tk);
    worst_discrete = std::max(worst_discrete, std::fabs(e - discrete) / (coupling * tk + 1e-12));
    worst_book = std::max(worst_book, std::fabs(e - book) / (1.2 * e0 * kappa * tk * kappa * T / 2 + coupling * tk + 1e-12));
  }
  const double e_end = loop.plant.indicated_heading_unwrapped_rad() - loop.plant.true_heading_rad();
  std::printf("heading error after 3/kappa: %.6f deg (book %.6f deg); worst |e - discrete| / tol %.3f, |e - book| / "
              "tol %.3f\n",
              e_end / kDeg, e0 * std::exp(-3.0) / kDeg, worst_discrete, worst_book);
  EXPECT_LT(worst_discrete, 1.0);
  EXPECT_LT(worst_book, 1.0);
  EXPECT_NEAR(e_end / (e0 * std::exp(-3.0)), 1.0, 1e-3);
}

// ---------------------------------------------------------------------------------------------------------
TEST(DirectionalGyroOracle, RollAtACornerKeepsTheRotorAxis) {
  // A 90° right turn at 3°/s and 250 m/s (bank atan(vω/g) = 53°), then straight: at the corner the case rolls
  // back level, the rotor — now across the aircraft, β ≈ −53° — does not: the gimbal angles are re-solved.
  // Without torques the rotor drifts against the level frame only at the Earth and transport rates, ≤
  // (ω^E + v/R) T = 1.1e-6 rad over the corner's tick (tolerance 3e-6); angles kept through the roll would
  // move it by ~0.9 rad.
  plants::DirectionalGyroPlantParams p = eastbound(250.0);
  p.vehicle.count = 1;
  p.vehicle.segments[0] = {.duration_ns = 30'000'000'000, .turn_rate = 3.0 * kDeg, .acceleration = 0.0};
  const plants::PlantTiming t{.tick_ns = 10'000'000, .substeps = 1, .seed = 1};
  plants::DirectionalGyroPlant plant(p, t);
  for (std::int64_t k = 0; k < 2999; ++k) plant.advance(k);
  const dynamics::Vec3 before = plant.rotor_axis_ned();
  const double bank_before = plant.bank_rad(), beta_before = plant.beta_rad();
  plant.advance(2999);
  const dynamics::Vec3 after = plant.rotor_axis_ned();
  std::printf("bank %.4f -> %.4f rad, beta %.4f -> %.4f rad, rotor axis moved %.3e rad\n", bank_before,
              plant.bank_rad(), beta_before, plant.beta_rad(), (after - before).norm());
  EXPECT_GT(bank_before - plant.bank_rad(), 0.9);
  EXPECT_GT(plant.beta_rad() - beta_before, 0.8);
  EXPECT_LT((after - before).norm(), 3e-6);
}

TEST(DirectionalGyroOracle, LawCheckRefusesOutOfRangeGains) {
  firmware::DirectionalGyroCorrectionParams p;
  p.H = 0.1;
  p.latitude = 50.0 * kDeg;
  p.speed = 250.0;
  p.heading_rate = 4.0 / 60.0;
  p.k = 0.005;
  const double T = 0.01;
  EXPECT_TRUE(firmware::check_directional_gyro_corrections(p, T).ok);
  auto refused = [&](auto edit) {
    firmware::DirectionalGyroCorrectionParams q = p;
    edit(q);
    return !firmware::check_directional_gyro_corrections(q, T).ok;
  };
  EXPECT_TRUE(refused([](auto& q) { q.heading_rate = 51.0; }));          // κT > 0.5
  EXPECT_FALSE(refused([](auto& q) { q.heading_rate = 50.0; }));
  EXPECT_TRUE(refused([&](auto& q) { q.k = 0.51 * q.H / T; }));          // kT/H > 0.5
  EXPECT_TRUE(refused([](auto& q) { q.k = -1e-3; }));
  EXPECT_TRUE(refused([](auto& q) { q.latitude = 86.0 * kDeg; }));
  EXPECT_TRUE(refused([](auto& q) { q.torque_limit_Nm = 1e-6; }));      // the compensation alone needs 1.0e-5 N m
  EXPECT_FALSE(refused([](auto& q) { q.torque_limit_Nm = 1e-6; q.compensate = false; }));
}

}  // namespace directional_gyro_test
}  // namespace gyrostab
