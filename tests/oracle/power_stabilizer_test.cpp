// Oracle tests of the power gyro stabilizer — plant sim/models/power_stabilizer.hpp, control law
// firmware/control/power_stabilizer_loops.hpp — against Magnus §14.3, (14.19)-(14.40), and the reference
// cases S1-S3 of docs/models/power-stabilizer.md: A = 1, B = 0.8, H = 50,
// k1 = k2 = 20; d = 0 ⇒ nutation Re λ = +0.40; d1 = d2 = 0.5 ⇒ −0.1625; k = 500 ⇒ +8.95).
//
// Closed loop: the firmware law is evaluated continuously, inside the derivative (ClosedLoop below maps the
// plant state to the power stabilizer's sensor frame, calls the law, and applies its actuator frame to the
// plant's inputs), so the
// loop is the book's continuous one and sampling contributes nothing to the measured rates. (The real 1 kHz
// loop with zero-order hold and one tick of latency, an effective delay of 1.5 ms, moves the S2 nutation root
// from −0.16249 to −0.16216 1/s and its frequency by +0.02 % — computed from the delayed characteristic
// equation; that loop is exercised by the scene runner.)
//
// Measurement: the nutation is read from the simulated inner-gimbal rate β'. Its extrema are located by
// parabolic interpolation; half the difference of consecutive extrema, (e_k − e_{k+1})/2, is the mode's
// amplitude with any slowly varying offset (the precession modes) cancelled to first order; the decay/growth
// rate is the least-squares slope of its log against time ("log-envelope slope"), the frequency π/(mean
// spacing of the extrema). For one damped mode e^{σt} cos ωt both are exact. The roots to compare with are
// the eigenvalues of the companion matrix of (14.23) / (14.29).
#include "sim/models/power_stabilizer.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <cstdio>
#include <cstring>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "firmware/control/power_stabilizer_loops.hpp"
#include "gyrostab_signals/power_stabilizer_frames.hpp"
#include "sim/analysis/zero_crossing_meter.hpp"
#include "sim/dynamics/gyroscopic_exponential.hpp"
#include "sim/dynamics/rk4.hpp"
#include "sim/dynamics/step_validation.hpp"
#include "sim/dynamics/substepping.hpp"
#include "tests/support/alloc_counter.hpp"
#include "sim/dynamics/eigenvalues.hpp"

namespace gyrostab {
namespace power_stabilizer_test {

using cd = std::complex<double>;
using SensorFrame = msg::power_stabilizer::SensorFrame;
using ActuatorFrame = msg::power_stabilizer::ActuatorFrame;
using firmware::GainCheckVerdict;
using firmware::PowerStabilizerConfig;
using firmware::PowerStabilizerLoops;
using firmware::PowerStabilizerOutput;
using firmware::PowerStabilizerStatusBit;
using models::BackEmfMotor;
using models::ElasticPlatform;
using models::FixedBase;
using models::RigidStructure;
using models::TorqueMotors;

// ---- the book's linear theory ---------------------------------------------------------------------------

// Roots of a polynomial c[0] λⁿ + ... + c[n] (c[0] ≠ 0) from its companion matrix.
template <int N>
Eigen::Matrix<cd, N, 1> polynomial_roots(const double (&c)[N + 1]) {
  Eigen::Matrix<double, N, N> C = Eigen::Matrix<double, N, N>::Zero();
  for (int i = 1; i < N; ++i) C(i, i - 1) = 1.0;
  for (int i = 0; i < N; ++i) C(i, N - 1) = -c[N - i] / c[0];
  return dynamics::eigenvalues<N>(C);
}

// Roots of (14.23), d1, d2 the total damping.
Eigen::Vector4cd roots_14_23(double A, double B, double H, double d1, double d2, double k1, double k2) {
  const double c[5] = {A * B, A * d2 + B * d1, H * H + d1 * d2, H * (k1 + k2), k1 * k2};
  return polynomial_roots<4>(c);
}
// Roots of the cubic factor of (14.29) (the fourth root is λ = 0, the neutral α).
Eigen::Vector3cd roots_14_29(double A, double B, double H, double d, double s, double r) {
  const double c[4] = {A * B, B * d * s, H * H, H * r * s};
  return polynomial_roots<3>(c);
}
// The nutation root: the one with the largest imaginary part.
template <class V>
cd nutation_root(const V& roots) {
  cd best = roots[0];
  for (int i = 1; i < roots.size(); ++i) {
    if (roots[i].imag() > best.imag()) best = roots[i];
  }
  return best;
}
template <class V>
double max_real_part(const V& roots) {
  double m = roots[0].real();
  for (int i = 1; i < roots.size(); ++i) m = std::max(m, roots[i].real());
  return m;
}

// ---- plant + firmware law, evaluated continuously -------------------------------------------------------

// Gimbal set with A (outer axis) = a, B (inner axis) = b, a ≥ b: rotor A^R = b, outer gimbal A^A = a − b.
models::GimbalGyroParams two_axis(double a, double b) {
  models::GimbalGyroParams p;
  p.AR = b;
  p.AA = a - b;
  p.CR = 1.0;
  return p;
}

template <class Plant>
SensorFrame sense(const Plant& plant, const typename Plant::State& x) {
  const models::PowerStabilizerSignals s = plant.signals(x);
  SensorFrame f{};
  f.alpha_rad = s.alpha;
  f.beta_rad = s.beta;
  f.alpha_rate_rad_s = s.alpha_rate;
  f.beta_rate_rad_s = s.beta_rate;
  return f;
}

// Plant with the law inside its derivative. Law: callable (const SensorFrame&, ActuatorFrame&).
template <class Plant, class Law>
struct ClosedLoop {
  static constexpr int kStateSize = Plant::kStateSize;
  using State = typename Plant::State;
  mutable Plant plant;
  Law law;

  void derivative(double t, const State& x, State& dx) const {
    ActuatorFrame command{};
    law(sense(plant, x), command);
    plant.inputs.M1K = command.motor1_torque_Nm;
    plant.inputs.M2K = command.motor2_torque_Nm;
    plant.inputs.u1 = command.motor1_voltage_V;
    plant.derivative(t, x, dx);
  }
  void project(State& /*x*/) const {}
  dynamics::GyroscopicPair gyroscopic_pair(const State& x) const { return plant.gyroscopic_pair(x); }
};
template <class Plant, class Law>
ClosedLoop<Plant, Law> close_loop(const Plant& plant, Law law) {
  return ClosedLoop<Plant, Law>{plant, law};
}

// The unchecked torque law (for gains the start-up check refuses: S1, S3).
auto unchecked_torque_law(const PowerStabilizerConfig& c) {
  return [c](const SensorFrame& in, ActuatorFrame& out) {
    const auto m =
        firmware::stabilization_torques(c, in.alpha_rad, in.beta_rad, in.alpha_rate_rad_s, in.beta_rate_rad_s);
    out.motor1_torque_Nm = m.M1;
    out.motor2_torque_Nm = m.M2;
  };
}
// The firmware's checked loops (compute(): gain check, law, saturation).
auto firmware_law(const PowerStabilizerLoops& loops) {
  return [&loops](const SensorFrame& in, ActuatorFrame& out) { loops.compute(in, out); };
}

// ---- measurement ----------------------------------------------------------------------------------------

struct ModeEstimate {
  double rate{0.0};       // Re λ [1/s]
  double frequency{0.0};  // |Im λ| [rad/s]
  int extrema{0};
  double max_abs{0.0};  // largest |signal| over the run
};

// Log-envelope slope and extremum spacing of uniformly sampled y(t), extrema in [t0, t1].
ModeEstimate measure_mode(const std::vector<double>& y, double h, double t0, double t1) {
  std::vector<double> te, ye;
  ModeEstimate m;
  for (std::size_t i = 1; i + 1 < y.size(); ++i) {
    m.max_abs = std::max(m.max_abs, std::abs(y[i]));
    const double a = y[i - 1], b = y[i], c = y[i + 1];
    const bool is_max = b > a && b >= c, is_min = b < a && b <= c;
    if (!is_max && !is_min) continue;
    const double den = a - 2.0 * b + c;
    const double s = 0.5 * (a - c) / den;
    const double t = (static_cast<double>(i) + s) * h;
    if (t < t0 || t > t1) continue;
    te.push_back(t);
    ye.push_back(b - 0.25 * (a - c) * s);
  }
  m.extrema = static_cast<int>(te.size());
  if (te.size() < 4) return m;
  // Least squares of ln((e_k − e_{k+1})/2 in magnitude) on the mid-times.
  double st = 0, sl = 0, stt = 0, stl = 0;
  const double n = static_cast<double>(te.size() - 1);
  for (std::size_t k = 0; k + 1 < te.size(); ++k) {
    const double t = 0.5 * (te[k] + te[k + 1]);
    const double l = std::log(0.5 * std::abs(ye[k] - ye[k + 1]));
    st += t;
    sl += l;
    stt += t * t;
    stl += t * l;
  }
  m.rate = (n * stl - st * sl) / (n * stt - st * st);
  m.frequency = std::numbers::pi * static_cast<double>(te.size() - 1) / (te.back() - te.front());
  return m;
}

// Integrate `model` from x for `duration` at step h, recording β' after every step.
template <template <class> class Integrator, class Model>
std::vector<double> run_beta_rate(const Model& model, typename Model::State x, double h, double duration) {
  Integrator<Model> integ(model);
  const long n = std::lround(duration / h);
  std::vector<double> y;
  y.reserve(static_cast<std::size_t>(n) + 1);
  y.push_back(x[3]);
  for (long i = 0; i < n; ++i) {
    integ.step(static_cast<double>(i) * h, h, x);
    y.push_back(x[3]);
  }
  return y;
}

// S-cases: A = 1, B = 0.8, H = 50.
PowerStabilizerConfig s_case(double d, double k) {
  PowerStabilizerConfig c;
  c.A = 1.0;
  c.B = 0.8;
  c.H = 50.0;
  c.d1 = c.d2 = d;
  c.k1 = c.k2 = k;
  c.torque_limit_Nm[0] = c.torque_limit_Nm[1] = 1e6;  // saturation never active in the oracle runs
  return c;
}
using RigidTorquePlant = models::PowerStabilizer<FixedBase, TorqueMotors, RigidStructure>;

// Simulate the torque loops on the full gimbal gyro with a small rate kick α'(0) = kick (an impulsive
// disturbance on axis 1) and measure the nutation on [t0, t1].
template <template <class> class Integrator, class Law>
ModeEstimate simulate_torque_loop(const PowerStabilizerConfig& c, Law law, double kick, double h, double t0,
                                  double t1) {
  const RigidTorquePlant plant(two_axis(c.A, c.B));
  const auto loop = close_loop(plant, law);
  const auto y =
      run_beta_rate<Integrator>(loop, RigidTorquePlant::make_state(0, 0, kick, 0, c.H), h, t1 + 0.05);
  return measure_mode(y, h, t0, t1);
}

// ---- (14.23): reference cases S1-S3 ---------------------------------------------------------------------

// The oracle itself: the companion-matrix roots reproduce the reference S1-S3 values.
TEST(PowerStabilizerOracle, CharacteristicRootsReproduceDigestCasesS1S2S3) {
  const cd s1 = nutation_root(roots_14_23(1, 0.8, 50, 0, 0, 20, 20));
  const cd s2 = nutation_root(roots_14_23(1, 0.8, 50, 0.5, 0.5, 20, 20));
  const cd s3 = nutation_root(roots_14_23(1, 0.8, 50, 0.5, 0.5, 500, 500));
  std::printf("nutation roots: S1 %.6f%+.4fi, S2 %.6f%+.4fi, S3 %.5f%+.4fi\n", s1.real(), s1.imag(),
              s2.real(), s2.imag(), s3.real(), s3.imag());
  // The reference values are given to 2-4 significant digits: +0.40, −0.1625, +8.95.
  EXPECT_NEAR(s1.real(), 0.40, 5e-4);
  EXPECT_NEAR(s2.real(), -0.1625, 5e-5);
  EXPECT_NEAR(s3.real(), 8.95, 5e-3);
  // S1's precession roots are −0.40 (reference), where precession theory (14.24) says −k/H = −0.4 and stable.
  const Eigen::Vector4cd r1 = roots_14_23(1, 0.8, 50, 0, 0, 20, 20);
  for (int i = 0; i < 4; ++i) {
    if (std::abs(r1[i].imag()) < 1.0) {
      EXPECT_NEAR(r1[i].real(), -0.40, 5e-4);
    }
  }
}

// S1: no damping ⇒ the nutation is self-excited; it grows at Re λ of (14.23)'s nutation root. The start-up
// check refuses these gains; the law is run unchecked to show why.
TEST(PowerStabilizerOracle, WithoutDampingTheNutationGrowsAtTheRootOf14_23) {
  const PowerStabilizerConfig c = s_case(0.0, 20.0);
  const cd root = nutation_root(roots_14_23(c.A, c.B, c.H, 0, 0, c.k1, c.k2));
  // RK4 at 0.2 ms: h|λ| = 0.011, per-step relative error (h|λ|)⁵/120 ≈ 1.5e-12 ⇒ rate error ≲ 1e-8 1/s.
  // Kick 1e-4 rad/s: angles ≤ 3e-4 rad after the e^{0.4·12} growth, nonlinear shifts ≲ 1e-7 relative.
  // Window from 2 s: the precession pair (−0.40) is then e^{−1.6} smaller relative to the nutation.
  const ModeEstimate m =
      simulate_torque_loop<dynamics::Rk4>(c, unchecked_torque_law(c), 1e-4, 2e-4, 2.0, 12.0);
  std::printf("S1 (d = 0): measured Re λ %.6f, ω %.5f over %d extrema; root %.6f%+.5fi; max |β'| %.2e\n",
              m.rate, m.frequency, m.extrema, root.real(), root.imag(), m.max_abs);
  EXPECT_GT(m.rate, 0.0) << "the undamped loop must be unstable";
  // Issue: within 2 %. The error budget above is < 1e-4 relative; the second bound is 10× that.
  EXPECT_NEAR(m.rate / root.real(), 1.0, 0.02);
  EXPECT_NEAR(m.rate / root.real(), 1.0, 1e-3);
  EXPECT_NEAR(m.frequency / root.imag(), 1.0, 1e-4);
  EXPECT_LT(m.max_abs / root.imag(), 1e-3);  // angle amplitude |β'|/ω stays small: the linear theory applies

  const auto check = firmware::check_power_stabilizer_gains(c);
  EXPECT_FALSE(check.accepted);
  EXPECT_EQ(check.verdict, GainCheckVerdict::kNoDamping) << check.reason;
  EXPECT_EQ(check.k_max_equal, 0.0);
}

// S2: with rate damping through the motors the nutation decays; measured decay rate and frequency match the
// root of (14.23). Run with the firmware's checked loops (compute()), under RK4 at 0.2 ms and under the
// default plant integrator (gyro-exponential) at the 1 ms scene step.
TEST(PowerStabilizerOracle, RateDampingDecaysTheNutationAtTheRootOf14_23) {
  const PowerStabilizerConfig c = s_case(0.5, 20.0);
  const PowerStabilizerLoops loops(c);
  ASSERT_TRUE(loops.armed()) << loops.gain_check().reason;
  const cd root = nutation_root(roots_14_23(c.A, c.B, c.H, c.d1, c.d2, c.k1, c.k2));
  // Window 3-15 s: the precession pair decays at 0.40, faster than the nutation (0.1625), so it fades from
  // β'; what remains is removed by the peak-to-peak amplitude.
  const ModeEstimate rk4 = simulate_torque_loop<dynamics::Rk4>(c, firmware_law(loops), 1e-3, 2e-4, 3.0, 15.0);
  const ModeEstimate exp =
      simulate_torque_loop<dynamics::GyroscopicExponential>(c, firmware_law(loops), 1e-3, 1e-3, 3.0, 15.0);
  for (const auto& [name, m] : {std::pair{"rk4 0.2 ms", rk4}, std::pair{"gyro-exponential 1 ms", exp}}) {
    std::printf("S2 (d = 0.5, %s): measured Re λ %.6f, ω %.5f over %d extrema; root %.6f%+.5fi\n", name,
                m.rate, m.frequency, m.extrema, root.real(), root.imag());
    EXPECT_LT(m.rate, 0.0) << name;
    // Issue: within 2 %.
    EXPECT_NEAR(m.rate / root.real(), 1.0, 0.02) << name;
    EXPECT_NEAR(m.frequency / root.imag(), 1.0, 0.02) << name;
    // Tighter: RK4's error is ~1e-8 1/s (as S1); gyro-exponential at hω_N = 0.056 midpoint-samples the loop
    // terms, an error ~(hω)²/24 = 1.3e-4 of their share of Re λ ((k1+k2)/2H = 0.4 and (Ad2+Bd1)/2AB = 0.56):
    // ≲ 1e-4 1/s, 0.1 % of 0.1625. Bound 0.3 % for both.
    EXPECT_NEAR(m.rate / root.real(), 1.0, 3e-3) << name;
    EXPECT_NEAR(m.frequency / root.imag(), 1.0, 1e-4) << name;
  }
}

// S3: gains far above the (14.25) bound (k = 500 against k_max = 28.1): the nutation grows at +8.95/s.
TEST(PowerStabilizerOracle, GainsTooHighForTheDampingMakeTheNutationGrow) {
  const PowerStabilizerConfig c = s_case(0.5, 500.0);
  const cd root = nutation_root(roots_14_23(c.A, c.B, c.H, c.d1, c.d2, c.k1, c.k2));
  // Kick 1e-9 rad/s, growth e^{8.95·1.5} = 7e5: angles stay ≲ 2e-5 rad. RK4 at 0.1 ms: h|λ| = 0.006.
  // Window 0.5-1.5 s: the precession pair (−9.5) is gone by e^{−18·0.5} relative to the nutation.
  const ModeEstimate m =
      simulate_torque_loop<dynamics::Rk4>(c, unchecked_torque_law(c), 1e-9, 1e-4, 0.5, 1.5);
  std::printf("S3 (k = 500): measured Re λ %.5f, ω %.5f over %d extrema; root %.5f%+.5fi; max |β'| %.2e\n",
              m.rate, m.frequency, m.extrema, root.real(), root.imag(), m.max_abs);
  EXPECT_NEAR(m.rate / root.real(), 1.0, 0.02);  // issue: 2 %
  EXPECT_NEAR(m.rate / root.real(), 1.0, 1e-3);  // error budget as S1
  EXPECT_NEAR(m.frequency / root.imag(), 1.0, 1e-4);
  const auto check = firmware::check_power_stabilizer_gains(c);
  EXPECT_FALSE(check.accepted);
  EXPECT_EQ(check.verdict, GainCheckVerdict::kHurwitzD2) << check.reason;
  EXPECT_LT(check.D2, 0.0);
  EXPECT_NEAR(check.k_max_equal, 28.1249, 1e-3);  // 2HPS/(4ABH² + S²) = 225022.5/8000.81
}

// ---- (14.25): the start-up gain check -------------------------------------------------------------------

// The check's bound is the true stability boundary: on both sides of it (±0.1 % of the gains) the check
// accepts/refuses exactly when the companion-matrix roots of (14.23) are all in the left half-plane, for
// several dampings, gain ratios and passive bearing damping.
TEST(PowerStabilizerGainCheck, AcceptsInsideAndRefusesOutsideTheHurwitzBoundary) {
  struct Case {
    double d1, d2, ratio, bearing;  // k2 = ratio k1; bearing damping on both axes
  };
  for (const Case cs : {Case{0.5, 0.5, 1.0, 0.0}, Case{0.2, 1.5, 1.0, 0.0}, Case{0.5, 0.5, 0.1, 0.0},
                        Case{2.0, 0.3, 4.0, 0.0}, Case{0.3, 0.3, 1.0, 0.2}}) {
    PowerStabilizerConfig c = s_case(0.0, 1.0);
    c.d1 = cs.d1;
    c.d2 = cs.d2;
    c.bearing_d1 = c.bearing_d2 = cs.bearing;
    c.k1 = 10.0;
    c.k2 = cs.ratio * 10.0;
    const auto probe = firmware::check_power_stabilizer_gains(c);
    ASSERT_GT(probe.gain_scale_max, 0.0);
    if (cs.ratio == 1.0) {
      EXPECT_NEAR(probe.k1_max, probe.k_max_equal, 1e-9 * probe.k_max_equal);
    }
    for (const double f : {0.999, 1.001}) {
      c.k1 = f * probe.k1_max;
      c.k2 = f * probe.k2_max;
      const auto check = firmware::check_power_stabilizer_gains(c);
      const double d1 = c.d1 + c.bearing_d1, d2 = c.d2 + c.bearing_d2;
      const double re = max_real_part(roots_14_23(c.A, c.B, c.H, d1, d2, c.k1, c.k2));
      std::printf("d = (%.2f, %.2f) + %.1f, k2/k1 = %.1f: k1 = %.4f (%.3f × bound): %s, max Re λ = %+.3e\n",
                  cs.d1, cs.d2, cs.bearing, cs.ratio, c.k1, f, check.accepted ? "accepted" : check.reason,
                  re);
      if (f < 1.0) {
        EXPECT_TRUE(check.accepted) << check.reason;
        EXPECT_LT(re, 0.0);
        EXPECT_GT(check.D3, 0.0);
      } else {
        EXPECT_FALSE(check.accepted);
        EXPECT_TRUE(check.verdict == GainCheckVerdict::kHurwitzD2 ||
                    check.verdict == GainCheckVerdict::kHurwitzD3)
            << check.reason;
        EXPECT_GT(re, 0.0);
      }
    }
    // D3 is the binding condition: D2 alone would allow σ < P S/(AB H (k1 + k2)), a factor
    // 1 + S² k1 k2/(AB H² (k1 + k2)²) (≈ 1 + 1e-4 here) above σ_max. Between the two, D2 > 0 but D3 < 0 and
    // a root is already in the right half-plane (Re λ ~ +1e-8, far above the companion solver's ~1e-12).
    const double d1 = c.d1 + c.bearing_d1, d2 = c.d2 + c.bearing_d2, k1 = 10.0, k2 = cs.ratio * 10.0;
    const double S = c.A * d2 + c.B * d1, P = c.H * c.H + d1 * d2;
    const double sigma_D2 = P * S / (c.A * c.B * c.H * (k1 + k2));
    ASSERT_GT(sigma_D2, probe.gain_scale_max);
    const double sigma_gap = 0.5 * (sigma_D2 + probe.gain_scale_max);
    c.k1 = sigma_gap * k1;
    c.k2 = sigma_gap * k2;
    const auto gap = firmware::check_power_stabilizer_gains(c);
    EXPECT_EQ(gap.verdict, GainCheckVerdict::kHurwitzD3) << gap.reason;
    EXPECT_GT(gap.D2, 0.0);
    EXPECT_GT(max_real_part(roots_14_23(c.A, c.B, c.H, d1, d2, c.k1, c.k2)), 0.0);
  }
}

// And in the simulated closed loop: 10 % inside the bound the nutation decays, 10 % outside it grows, each at
// its root's rate.
TEST(PowerStabilizerGainCheck, SimulatedLoopDecaysInsideAndGrowsOutsideTheBound) {
  const PowerStabilizerConfig s2 = s_case(0.5, 20.0);
  const double k_max = firmware::check_power_stabilizer_gains(s2).k_max_equal;
  for (const double f : {0.9, 1.1}) {
    const PowerStabilizerConfig c = s_case(0.5, f * k_max);
    const cd root = nutation_root(roots_14_23(c.A, c.B, c.H, c.d1, c.d2, c.k1, c.k2));
    // Window 3-20 s; RK4 0.2 ms as S1. |Re λ| ≈ 0.05: the envelope changes by e^{0.85} over the window.
    const ModeEstimate m =
        simulate_torque_loop<dynamics::Rk4>(c, unchecked_torque_law(c), 1e-3, 2e-4, 3.0, 20.0);
    std::printf("k = %.3f × k_max = %.4f: measured Re λ %+.6f, root %+.6f\n", f, c.k1, m.rate, root.real());
    EXPECT_EQ(m.rate > 0.0, f > 1.0);
    EXPECT_EQ(firmware::check_power_stabilizer_gains(c).accepted, f < 1.0);
    // Issue: 2 % of the (small) rate; the RK4 budget of S1 (≲ 1e-8 1/s) is far inside it.
    EXPECT_NEAR(m.rate / root.real(), 1.0, 0.02);
  }
}

// Every refusal says why and with which equation; the refused loops output the safe command.
TEST(PowerStabilizerGainCheck, RefusalsNameTheViolatedCondition) {
  auto verdict = [](auto edit) {
    PowerStabilizerConfig c = s_case(0.5, 20.0);
    edit(c);
    return firmware::check_power_stabilizer_gains(c).verdict;
  };
  EXPECT_EQ(verdict([](PowerStabilizerConfig&) {}), GainCheckVerdict::kAccepted);
  EXPECT_EQ(verdict([](PowerStabilizerConfig& c) { c.H = 0.0; }), GainCheckVerdict::kInvalidPlant);
  EXPECT_EQ(verdict([](PowerStabilizerConfig& c) { c.B = std::nan(""); }), GainCheckVerdict::kInvalidPlant);
  EXPECT_EQ(verdict([](PowerStabilizerConfig& c) { c.d2 = -0.1; }), GainCheckVerdict::kInvalidGain);
  EXPECT_EQ(verdict([](PowerStabilizerConfig& c) { c.k1 = INFINITY; }), GainCheckVerdict::kInvalidGain);
  EXPECT_EQ(verdict([](PowerStabilizerConfig& c) { c.torque_limit_Nm[1] = 0.0; }),
            GainCheckVerdict::kInvalidLimit);
  EXPECT_EQ(verdict([](PowerStabilizerConfig& c) { c.k2 = 0.0; }), GainCheckVerdict::kNoStiffness);
  EXPECT_EQ(verdict([](PowerStabilizerConfig& c) { c.k1 = -5.0; }), GainCheckVerdict::kNoStiffness);
  EXPECT_EQ(verdict([](PowerStabilizerConfig& c) { c.d1 = c.d2 = 0.0; }), GainCheckVerdict::kNoDamping);
  // Passive bearing damping counts: no commanded damping, but bearings of 0.5 ⇒ S2 again.
  EXPECT_EQ(verdict([](PowerStabilizerConfig& c) {
              c.d1 = c.d2 = 0.0;
              c.bearing_d1 = c.bearing_d2 = 0.5;
            }),
            GainCheckVerdict::kAccepted);
  EXPECT_EQ(verdict([](PowerStabilizerConfig& c) { c.k1 = c.k2 = 500.0; }), GainCheckVerdict::kHurwitzD2);
  // Between the D3 bound 28.1249 and the D2 bound P S/(2 AB H) = 28.1278 only D3 fails.
  EXPECT_EQ(verdict([](PowerStabilizerConfig& c) { c.k1 = c.k2 = 28.1265; }), GainCheckVerdict::kHurwitzD3);
  // Voltage mode.
  EXPECT_EQ(verdict([](PowerStabilizerConfig& c) { c.output = PowerStabilizerOutput::kBackEmfVoltage; }),
            GainCheckVerdict::kAccepted);
  EXPECT_EQ(verdict([](PowerStabilizerConfig& c) {
              c.output = PowerStabilizerOutput::kBackEmfVoltage;
              c.r = 13.0;
            }),
            GainCheckVerdict::kHurwitzD2);
  EXPECT_EQ(verdict([](PowerStabilizerConfig& c) {
              c.output = PowerStabilizerOutput::kBackEmfVoltage;
              c.d_emf = 0.0;
            }),
            GainCheckVerdict::kNoDamping);
  EXPECT_EQ(verdict([](PowerStabilizerConfig& c) {
              c.output = PowerStabilizerOutput::kBackEmfVoltage;
              c.r = 0.0;
            }),
            GainCheckVerdict::kNoStiffness);
  EXPECT_EQ(verdict([](PowerStabilizerConfig& c) {
              c.output = PowerStabilizerOutput::kBackEmfVoltage;
              c.s = 0.0;
            }),
            GainCheckVerdict::kInvalidGain);
  EXPECT_EQ(verdict([](PowerStabilizerConfig& c) {
              c.output = PowerStabilizerOutput::kBackEmfVoltage;
              c.voltage_limit_V = -1.0;
            }),
            GainCheckVerdict::kInvalidLimit);

  const PowerStabilizerLoops refused(s_case(0.0, 20.0));
  EXPECT_FALSE(refused.armed());
  EXPECT_NE(std::string(refused.gain_check().reason).find("(14.23)"), std::string::npos);
  SensorFrame in{};
  in.beta_rad = 0.1;
  ActuatorFrame out{};
  refused.compute(in, out);
  EXPECT_EQ(out.motor1_torque_Nm, 0.0);
  EXPECT_EQ(out.motor2_torque_Nm, 0.0);
  EXPECT_EQ(out.motor1_voltage_V, 0.0);
  EXPECT_EQ(out.motor2_voltage_V, 0.0);
  EXPECT_TRUE(msg::has(out.status, msg::FaultBit::kSafeState));
  EXPECT_NE(out.status & firmware::bit(PowerStabilizerStatusBit::kGainsRefused), 0u);
}

// ---- (14.21): constant disturbances ---------------------------------------------------------------------

// Constant M1^S, M2^S are balanced by the motors at α0 = −M20^S/k2, β0 = M10^S/k1: the stiffness is k. In
// the full model the rest point satisfies this exactly (no gyroscopic or inertia term at rest).
TEST(PowerStabilizerOracle, ConstantDisturbancesAreHeldAtMOverK) {
  const PowerStabilizerConfig c = s_case(0.5, 20.0);
  const PowerStabilizerLoops loops(c);
  RigidTorquePlant plant(two_axis(c.A, c.B));
  plant.inputs.M1S = 1.0;
  plant.inputs.M2S = 0.5;
  auto loop = close_loop(plant, firmware_law(loops));
  auto x = RigidTorquePlant::make_state(0, 0, 0, 0, c.H);
  dynamics::GyroscopicExponential<decltype(loop)> integ(loop);
  for (int i = 0; i < 60'000; ++i) integ.step(i * 1e-3, 1e-3, x);  // 60 s
  std::printf("constant disturbance: α = %.9f (−M2/k2 = %.9f), β = %.9f (M1/k1 = %.9f)\n", x[0], -0.5 / c.k2,
              x[1], 1.0 / c.k1);
  // Slowest transient: the nutation, e^{−0.1625·60} = 6e-5 of its ~MB/H² = 3e-4 rad start: ≲ 2e-8 rad.
  EXPECT_NEAR(x[0], -0.5 / c.k2, 1e-7);
  EXPECT_NEAR(x[1], 1.0 / c.k1, 1e-7);
}

// ---- (14.26)-(14.30): back-EMF motor --------------------------------------------------------------------

// Gyro with A^K = 0.6 (A^A 0.1 + A^R 0.5), B = 0.8 (A^R 0.5 + B^J 0.3); motor κ = 10, I = 4e-3 ⇒ κ²I = 0.4,
// A = 1.0; s = 2 N m/V, d = 0.25 V s/rad ⇒ r_max = H d/A = 12.5 V/rad (20.8 if κ²I were forgotten).
models::GimbalGyroParams back_emf_gyro() {
  models::GimbalGyroParams p;
  p.AR = 0.5;
  p.BJ = 0.3;
  p.AA = 0.1;
  p.CR = 1.0;
  return p;
}
using BackEmfPlant = models::PowerStabilizer<FixedBase, BackEmfMotor, RigidStructure>;

PowerStabilizerConfig back_emf_config(double A, double r) {
  PowerStabilizerConfig c;
  c.output = PowerStabilizerOutput::kBackEmfVoltage;
  c.A = A;
  c.B = 0.8;
  c.H = 50.0;
  c.r = r;
  c.d_c = 0.0;  // the damping is the motor's back-EMF alone, as in the book
  c.s = 2.0;
  c.d_emf = 0.25;
  c.voltage_limit_V = 1e6;
  return c;
}

// The voltage law, unchecked (the outside case is refused by the check): u1 = −r β − d_c α', on the back-EMF
// plant, from a rate kick α'(0) = 1e-3 rad/s; nutation measured on 5-40 s (the real root −r s/H ≈ −0.5 has
// faded by then; the nutation envelope changes by e^{±0.9}). `root` receives the nutation root of (14.29).
template <template <class> class Integrator>
ModeEstimate simulate_back_emf(double r, double h, cd& root) {
  const BackEmfPlant plant(back_emf_gyro(), BackEmfMotor{2.0, 0.25, 10.0, 4e-3});
  const PowerStabilizerConfig c = back_emf_config(plant.outer_axis_inertia(), r);
  auto law = [c](const SensorFrame& in, ActuatorFrame& out) {
    out.motor1_voltage_V = firmware::back_emf_voltage(c, in.beta_rad, in.alpha_rate_rad_s);
  };
  root = nutation_root(roots_14_29(plant.outer_axis_inertia(), 0.8, 50.0, 0.25, 2.0, r));
  const auto y = run_beta_rate<Integrator>(close_loop(plant, law),
                                           BackEmfPlant::make_state(0, 0, 1e-3, 0, 50.0), h, 40.05);
  return measure_mode(y, h, 5.0, 40.0);
}

// (14.30): stable iff r < H d / A. 10 % inside it decays, 10 % outside it grows, at the cubic's rate; the
// check accepts the first and refuses the second with the bound.
TEST(PowerStabilizerOracle, BackEmfLoopIsStableIffRBelowHdOverA) {
  const BackEmfPlant plant(back_emf_gyro(), BackEmfMotor{2.0, 0.25, 10.0, 4e-3});
  ASSERT_NEAR(plant.outer_axis_inertia(), 1.0, 1e-12);  // A^K + κ²I
  const double r_max = 50.0 * 0.25 / 1.0;
  for (const double f : {0.9, 1.1}) {
    cd root;
    // RK4 at 0.2 ms: error budget as S1 (≲ 1e-8 1/s). gyro-exponential at the 1 ms scene step: the back-EMF
    // damping is in its exact flow, the r loop is midpoint-sampled, an error ≈ (hω)²/24 = 1.3e-4 of the
    // loop's share r s/(2H) ≈ 0.25 of Re λ: ≈ 3e-5 1/s, 0.13 % of |Re λ| = 0.025.
    const ModeEstimate rk4 = simulate_back_emf<dynamics::Rk4>(f * r_max, 2e-4, root);
    const ModeEstimate exp = simulate_back_emf<dynamics::GyroscopicExponential>(f * r_max, 1e-3, root);
    const auto check = firmware::check_power_stabilizer_gains(back_emf_config(1.0, f * r_max));
    std::printf(
        "back-EMF r = %.3f × Hd/A: measured Re λ %+.7f (rk4), %+.7f (gyro-exp), ω %.4f; root of (14.29)"
        " %+.7f%+.4fi; check: %s (r_max %.4f)\n",
        f, rk4.rate, exp.rate, rk4.frequency, root.real(), root.imag(), check.reason, check.r_max);
    for (const ModeEstimate& m : {rk4, exp}) {
      EXPECT_EQ(m.rate > 0.0, f > 1.0) << "growth sign at r = " << f << " r_max";
      EXPECT_NEAR(m.rate / root.real(), 1.0, 0.02);  // issue: 2 %
      EXPECT_NEAR(m.frequency / root.imag(), 1.0, 1e-4);
    }
    EXPECT_NEAR(rk4.rate / root.real(), 1.0, 1e-4);
    EXPECT_NEAR(exp.rate / root.real(), 1.0, 5e-3);
    EXPECT_EQ(check.accepted, f < 1.0);
    EXPECT_NEAR(check.r_max, r_max, 1e-12 * r_max);
    if (f > 1.0) {
      EXPECT_EQ(check.verdict, GainCheckVerdict::kHurwitzD2) << check.reason;
    }
  }
}

// The reflected motor inertia κ²I belongs in A: at r = 15 V/rad (between H d/A = 12.5 and H d/A^K = 20.8) the
// plant's loop grows; a controller configured with A^K alone would accept it, with A^K + κ²I refuses it.
TEST(PowerStabilizerOracle, ReflectedMotorInertiaLowersTheBackEmfBound) {
  cd root;
  const ModeEstimate m = simulate_back_emf<dynamics::GyroscopicExponential>(15.0, 1e-3, root);
  std::printf("back-EMF r = 15: measured Re λ %+.6f, root %+.6f\n", m.rate, root.real());
  EXPECT_GT(m.rate, 0.0);
  EXPECT_NEAR(m.rate / root.real(), 1.0, 0.02);
  EXPECT_TRUE(firmware::check_power_stabilizer_gains(back_emf_config(0.6, 15.0)).accepted);
  EXPECT_FALSE(firmware::check_power_stabilizer_gains(back_emf_config(1.0, 15.0)).accepted);
}

// ---- (14.31)-(14.37): structural elasticity -------------------------------------------------------------

// Elastic platform, quasi-static regime: A^K = 1, B = 0.8, H = 50, c = 2e4 N m/rad, A^P = 200 kg m²; the
// motor idle (M1^K = 0: (14.37) is the platform's own frequency). c* = c H²/(cB + H²) = 2702.7 N m/rad,
// ω^P = sqrt(c*/A^P) = 3.676 rad/s; the elastic/nutation mode is at 153 rad/s, 42× higher.
// Exact linear theory (B β' = H α integrated, no other approximation):
//   A^K A^P Ω² − [(H²/B + c) A^P + c A^K] Ω + c H²/B = 0,   Ω = ω²;
// the quasi-static (14.37) drops the gyro's inertia A^K α'', a relative error in ω² of
// ε = A^K c B/(A^P (cB + H²)) = 4.3e-3 to first order (ω low by ε/2).
using ElasticPlant = models::PowerStabilizer<FixedBase, TorqueMotors, ElasticPlatform>;

TEST(PowerStabilizerOracle, ElasticPlatformFrequencyIsOmegaP_14_37) {
  const double AK = 1.0, B = 0.8, H = 50.0, c = 2.0e4, AP = 200.0;
  const ElasticPlant plant(two_axis(AK, B), TorqueMotors{}, ElasticPlatform{c, AP});
  const double c_star = c * H * H / (c * B + H * H);
  const double w_book = std::sqrt(c_star / AP);  // (14.37)
  const double qa = AK * AP, qb = (H * H / B + c) * AP + c * AK, qc = c * H * H / B;
  const double Omega_slow = (qb - std::sqrt(qb * qb - 4.0 * qa * qc)) / (2.0 * qa);
  const double w_exact = std::sqrt(Omega_slow);
  const double eps = AK * c * B / (AP * (c * B + H * H));

  // Sub-steps from the step validation of the 1 ms tick on the fastest mode (RK4).
  const ElasticPlant::State x_lin = ElasticPlant::make_state(0, 0, 0, 0, H, 0, 0);
  const dynamics::Mode fastest = dynamics::fastest_mode(plant, 0.0, x_lin, "elastic-nutation");
  const dynamics::StepCheck step = dynamics::check_step(dynamics::Method::kRk4, fastest, 1e-3);
  std::printf("%s\n", step.message.c_str());
  ASSERT_LE(step.substeps_needed, 4);

  // Pure slow mode: φ = φ0, α = c φ0/(H²/B + c − A^K Ω) (≈ (14.33)), β' = H α/B, at rest otherwise.
  const double phi0 = 1e-5;
  const double alpha0 = c * phi0 / (H * H / B + c - AK * Omega_slow);
  ElasticPlant::State x = ElasticPlant::make_state(alpha0, 0, 0, H * alpha0 / B, H, phi0, 0);
  dynamics::Rk4<ElasticPlant> integ(plant);
  dynamics::SubstepDriver driver(integ, 1'000'000, step.substeps_needed);
  analysis::ZeroCrossingMeter meter;
  double alpha_max = 0, phi_max = 0;
  const long ticks = std::lround(20.5 * 2.0 * std::numbers::pi / w_book / 1e-3);  // 20 periods
  for (long k = 0; k < ticks; ++k) {
    driver.advance_tick(k, x);
    meter.add(static_cast<double>(k + 1) * 1e-3, x[5], x[6]);
    alpha_max = std::max(alpha_max, std::abs(x[0]));
    phi_max = std::max(phi_max, std::abs(x[5]));
  }
  const double w = meter.angular_frequency();
  std::printf(
      "elastic platform: ω measured %.7f rad/s, exact linear %.7f, (14.37) %.7f (ε = %.2e); α/φ %.6f,"
      " (14.33) %.6f\n",
      w, w_exact, w_book, eps, alpha_max / phi_max, c * B / (c * B + H * H));
  ASSERT_GE(meter.crossings(), 20);
  // Against the exact linear root: RK4 phase error (hω)⁴/120 ≈ 1.5e-12 at the slow mode; Hermite crossings at
  // 1700 samples per period ~1e-10; amplitude 1e-5 rad, β ≤ 2e-4 rad: nonlinear shift ≲ 1e-8. Bound 1e-6.
  EXPECT_NEAR(w / w_exact, 1.0, 1e-6);
  // Against the book's quasi-static (14.37): within the neglected-inertia size ε (the first-order
  // deviation is −ε/2 = −0.22 %; using c instead of c*, or the rigid c* = H²/B, errs by > 7 %).
  EXPECT_NEAR(w / w_book, 1.0, eps);
  EXPECT_LT(w, w_book);  // neglecting A^K α'' overestimates the frequency
  // (14.33) α = φ cB/(cB + H²): the neglected A^K term shifts it by A^K Ω/(H²/B + c) = 6e-4.
  EXPECT_NEAR(alpha_max / phi_max / (c * B / (c * B + H * H)), 1.0, 2e-3);
}

// Energy of the elastic option without damping, motor or disturbances: conserved by the true motion; a sign
// error in the shaft torque on either body would break it. Both modes excited.
TEST(PowerStabilizerOracle, ElasticPlatformConservesEnergy) {
  const ElasticPlant plant(two_axis(1.0, 0.8), TorqueMotors{}, ElasticPlatform{2.0e4, 200.0});
  ElasticPlant::State x = ElasticPlant::make_state(1e-3, 2e-3, 0.05, -0.02, 50.0, -1e-3, 0.01);
  const double e0 = plant.energy(x);
  dynamics::Rk4<ElasticPlant> integ(plant);
  const double h = 1e-4;
  double worst = 0;
  for (int i = 0; i < 100'000; ++i) {  // 10 s
    integ.step(i * h, h, x);
    worst = std::max(worst, std::abs(plant.energy(x) / e0 - 1.0));
  }
  // RK4 on an undamped mode loses (hω)⁶/144 of amplitude per step: at ω = 153 rad/s, h = 0.1 ms, that is
  // 8.9e-14 per step, 8.9e-9 in amplitude and 1.8e-8 in energy over 1e5 steps at most. Bound 1e-7.
  std::printf("elastic platform energy: max relative drift %.2e over 10 s\n", worst);
  EXPECT_LT(worst, 1e-7);
}

// ---- the firmware step itself ---------------------------------------------------------------------------

TEST(PowerStabilizerLoopsUnit, TorqueLawSaturationAndStatusBits) {
  PowerStabilizerConfig c = s_case(0.5, 20.0);
  c.torque_limit_Nm[0] = 1.0;
  c.torque_limit_Nm[1] = 2.0;
  const PowerStabilizerLoops loops(c);
  ASSERT_TRUE(loops.armed());
  SensorFrame in{};
  in.alpha_rad = 0.01;          // α
  in.beta_rad = 0.02;           // β
  in.alpha_rate_rad_s = 0.4;    // α'
  in.beta_rate_rad_s = -0.2;    // β'
  ActuatorFrame out{};
  out.status =
      msg::bit(msg::FaultBit::kHoldingLastGood) | firmware::bit(PowerStabilizerStatusBit::kVoltageSaturated);
  out.tick = 7;
  out.motor1_voltage_V = 5.0;  // a stale voltage: the law zeroes the unused mode's values
  out.motor2_voltage_V = 5.0;
  loops.compute(in, out);
  // M1 = −20·0.02 − 0.5·0.4 = −0.6, M2 = 20·0.01 + 0.5·0.2 = 0.3: inside the limits.
  EXPECT_DOUBLE_EQ(out.motor1_torque_Nm, -0.6);
  EXPECT_DOUBLE_EQ(out.motor2_torque_Nm, 0.3);
  EXPECT_EQ(out.motor1_voltage_V, 0.0);
  EXPECT_EQ(out.motor2_voltage_V, 0.0);
  EXPECT_EQ(out.tick, 7u);  // header untouched
  EXPECT_EQ(out.status, msg::bit(msg::FaultBit::kHoldingLastGood)) << "own bits cleared, others kept";
  // Saturation: β = 0.1 ⇒ M1 = −2.2 → −1; α = 0.2 ⇒ M2 = 4.1 → 2.
  in.beta_rad = 0.1;
  in.alpha_rad = 0.2;
  loops.compute(in, out);
  EXPECT_EQ(out.motor1_torque_Nm, -1.0);
  EXPECT_EQ(out.motor2_torque_Nm, 2.0);
  EXPECT_NE(out.status & firmware::bit(PowerStabilizerStatusBit::kTorque1Saturated), 0u);
  EXPECT_NE(out.status & firmware::bit(PowerStabilizerStatusBit::kTorque2Saturated), 0u);
  // A NaN that got past the fault monitor: zero command, flagged.
  in.alpha_rate_rad_s = std::nan("");
  loops.compute(in, out);
  EXPECT_EQ(out.motor1_torque_Nm, 0.0);
  EXPECT_EQ(out.motor2_torque_Nm, 0.0);
  EXPECT_NE(out.status & firmware::bit(PowerStabilizerStatusBit::kNonFiniteCommand), 0u);
}

TEST(PowerStabilizerLoopsUnit, VoltageLawSaturationAndStatusBits) {
  PowerStabilizerConfig c = back_emf_config(1.0, 10.0);
  c.d_c = 0.1;
  c.voltage_limit_V = 24.0;
  const PowerStabilizerLoops loops(c);
  ASSERT_TRUE(loops.armed()) << loops.gain_check().reason;
  EXPECT_NEAR(loops.gain_check().r_max, 50.0 * 0.35 / 1.0, 1e-12);  // d = d_emf + d_c
  SensorFrame in{};
  in.beta_rad = 0.5;
  in.alpha_rate_rad_s = 2.0;
  ActuatorFrame out{};
  loops.compute(in, out);
  EXPECT_DOUBLE_EQ(out.motor1_voltage_V, -10.0 * 0.5 - 0.1 * 2.0);
  EXPECT_EQ(out.motor2_voltage_V, 0.0);
  EXPECT_EQ(out.motor1_torque_Nm, 0.0);
  EXPECT_EQ(out.motor2_torque_Nm, 0.0);
  EXPECT_EQ(out.status & firmware::kPowerStabilizerStatusMask, 0u);
  in.beta_rad = 3.0;
  loops.compute(in, out);
  EXPECT_EQ(out.motor1_voltage_V, -24.0);
  EXPECT_NE(out.status & firmware::bit(PowerStabilizerStatusBit::kVoltageSaturated), 0u);
}

// compute() is a pure function of (config, sensor frame) and allocates nothing.
TEST(PowerStabilizerLoopsUnit, ComputeIsPureAndAllocationFree) {
  const PowerStabilizerLoops loops(s_case(0.5, 20.0));
  SensorFrame in{};
  ActuatorFrame a{}, b{};
  double sum = 0;
  testing::AllocationCounter counter;
  for (int i = 0; i < 100'000; ++i) {
    in.alpha_rad = 1e-3 * std::sin(1e-3 * i);
    in.beta_rad = 1e-3 * std::cos(1e-3 * i);
    loops.compute(in, a);
    sum += a.motor1_torque_Nm;
  }
  EXPECT_EQ(counter.count(), 0u);
  loops.compute(in, b);
  EXPECT_EQ(std::memcmp(&a, &b, sizeof a), 0);
  EXPECT_TRUE(std::isfinite(sum));
}

}  // namespace power_stabilizer_test
}  // namespace gyrostab
