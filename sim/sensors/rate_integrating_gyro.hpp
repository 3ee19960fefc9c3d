// Single-degree-of-freedom gyro as a sensor with its own dynamics: the rotor's case (float or inner gimbal)
// turns about the output axis by β against a spring c2 and a damper d2 when the instrument case turns about
// the input axis. One model for the rate gyro (P), the rate-integrating gyro (I) and the double-integrating
// gyro (I²) of Magnus ch. 15, §15.1-15.3 (docs/models/rate-gyros.md); sim/sensors/rate_gyro.hpp is the
// measurement-chain model (bandwidth filter, noise, quantizer) of the same instrument when only its output
// matters — this header is the physics behind that filter.
//
// Book: (15.1) with c1 → ∞ (α = 0, the outer frame is the case), built on the master equation (10.22):
//   B β'' + d2 β' + (c2 + H Ω3) β = H Ω1 − B Ω2' + M            (case axes: 1 input, 2 output, 3 spin)
// P-gyro (c2 > 0):   steady  β = (H Ω1 − B Ω2')/(c2 + H Ω3)  (15.3),  ≈ (H/c2) Ω1 (15.4);  free motion
//                    (15.2) B β'' + d2 β' + c2 β = 0: natural frequency ω_n = sqrt(c2/B) (book: 10-60 Hz),
//                    damping ratio ζ = d2/(2 sqrt(B c2)); indicated rate (c2/H) β.
// I-gyro  (c2 = 0):  (15.12) B β'' + d2 β' ≈ H Ω1:  β' → (H/d2) Ω1 with T_z = B/d2 (15.13)-(15.14);
//                    β = β0 + (H/d2) ∫Ω1 dt (15.16); indicated angle (d2/H) β, gain H/d2 (book: ≈ 100).
//                    Steady under Ω3 ≠ 0: β = Ω1/Ω3 (15.11) — not small, the instrument saturates.
// I²-gyro (c2 = d2 = 0): β'' = (H/B) Ω1 (15.18); indicated double integral (B/H) β (15.19).
// M = torquer on the output axis [N m] (a platform's command torque, (16.1)); M/H is then a commanded rate.
//
// State [β (rad), β' (rad/s)]. Parameters (SI): B output-axis inertia [kg m²], d2 [N m s/rad], c2
// [N m/rad], H [N m s], T sample period [s], RK4 sub-steps per sample (0: chosen so that h |λ|max ≤ 0.05,
// giving an amplitude error ≲ 1e-9 per sample on the fastest mode).
// Inputs per sample: case rates (Ω1, Ω3) [rad/s] and Ω2' [rad/s²] at the start and end of the sample
// (linear in between, so a ramp is integrated exactly to RK4 order), torquer M [N m] (held).
// Assumptions (book): symmetric rotor at constant spin, small β (except the I-gyro saturation case), no
// structural compliance (the B + H²/c1 correction (9.21) is left out), no anisoelastic or coning terms
// (the coning error of Magnus §15.5 with the full case rate: single_axis_gyro_coning.hpp).
// Oracle: tests/oracle/rate_integrating_gyro_test.cpp — steady outputs (15.3), (15.4), (15.11), (15.15)-
// (15.16), (15.19); free-motion frequency and damping of (15.2); the I-gyro time constant (15.14); −3 dB
// bandwidth of the P-gyro from the transfer function; the turn-indicator reading (15.6).
// Hot path: update() is allocation-free, O(substeps).
// Docs: docs/models/rate-gyros.md#single-degree-of-freedom-gyro-magnus-151-153
#pragma once

#include <cmath>

namespace gyrostab::sensors {

enum class SingleAxisGyroKind {
  kRate,               // P: c2 > 0
  kIntegrating,        // I: c2 = 0, d2 > 0
  kDoubleIntegrating,  // I²: c2 = d2 = 0
};

struct SingleAxisGyroParams {
  double B{2e-5};             // output-axis inertia [kg m²]
  double d2{5e-3};            // output-axis damping [N m s/rad]
  double c2{1.0};             // output-axis spring [N m/rad]
  double H{0.01};             // spin momentum [N m s]
  double sample_period{1e-3};  // T [s]
  int substeps{0};            // RK4 steps per sample; 0: automatic

  SingleAxisGyroKind kind() const {
    if (c2 > 0.0) return SingleAxisGyroKind::kRate;
    return d2 > 0.0 ? SingleAxisGyroKind::kIntegrating : SingleAxisGyroKind::kDoubleIntegrating;
  }
  // nullptr if usable, else why not.
  const char* invalid_reason() const {
    const auto fin = [](double v) { return std::isfinite(v); };
    if (!(fin(B) && B > 0.0)) return "B must be finite and > 0";
    if (!(fin(H) && H > 0.0)) return "H must be finite and > 0";
    if (!(fin(d2) && d2 >= 0.0 && fin(c2) && c2 >= 0.0)) return "d2, c2 must be finite and >= 0";
    if (!(fin(sample_period) && sample_period > 0.0)) return "sample_period must be finite and > 0";
    if (substeps < 0 || substeps > 100000) return "substeps must lie in [0, 100000]";
    return nullptr;
  }
};

// Case motion at one instant, in the gyro's case axes (1 input, 2 output, 3 spin).
struct GyroCaseMotion {
  double Omega1{0.0};      // [rad/s]
  double Omega2_dot{0.0};  // [rad/s²]
  double Omega3{0.0};      // [rad/s]
};

class SingleAxisGyro {
 public:
  explicit SingleAxisGyro(const SingleAxisGyroParams& p = {}) : p_(p) {
    const double h_target = 0.05 / fastest_rate(p_, 0.0);
    n_ = p_.substeps > 0 ? p_.substeps
                         : static_cast<int>(std::ceil(p_.sample_period / h_target - 1e-9));
    if (n_ < 1) n_ = 1;
    h_ = p_.sample_period / n_;
  }

  const SingleAxisGyroParams& params() const { return p_; }
  int substeps() const { return n_; }

  // |λ|max of B λ² + d2 λ + (c2 + H Ω3) = 0 [1/s] (≥ a floor so that a free I²-gyro still gets a step).
  static double fastest_rate(const SingleAxisGyroParams& p, double Omega3) {
    const double k = p.c2 + p.H * Omega3;
    const double disc = p.d2 * p.d2 - 4.0 * p.B * k;
    const double r = disc >= 0.0 ? (p.d2 + std::sqrt(disc)) / (2.0 * p.B) : std::sqrt(k / p.B);
    return r > 1e-9 ? r : 1e-9;
  }

  double natural_frequency() const { return std::sqrt(p_.c2 / p_.B); }                // ω_n (15.2) [rad/s]
  double damping_ratio() const { return p_.d2 / (2.0 * std::sqrt(p_.B * p_.c2)); }    // ζ (15.2) [-]
  double time_constant() const { return p_.B / p_.d2; }                              // T_z (15.14) [s]

  void reset(double beta = 0.0, double beta_rate = 0.0) {
    beta_ = beta;
    beta_rate_ = beta_rate;
  }
  // Start at the steady P-gyro deflection (15.3) for a constant case motion.
  void reset_steady(const GyroCaseMotion& m) {
    beta_ = (p_.H * m.Omega1 - p_.B * m.Omega2_dot) / (p_.c2 + p_.H * m.Omega3);
    beta_rate_ = 0.0;
  }

  // One sample: integrates T with the case motion linear from m0 to m1 and the torquer M held; returns β.
  double update(const GyroCaseMotion& m0, const GyroCaseMotion& m1, double M = 0.0) {
    for (int k = 0; k < n_; ++k) {
      const double s0 = static_cast<double>(k) / n_, s1 = static_cast<double>(k + 1) / n_;
      const double sm = 0.5 * (s0 + s1);
      double b1, v1, b2, v2, b3, v3, b4, v4;
      accel(m0, m1, s0, M, beta_, beta_rate_, b1, v1);
      accel(m0, m1, sm, M, beta_ + 0.5 * h_ * b1, beta_rate_ + 0.5 * h_ * v1, b2, v2);
      accel(m0, m1, sm, M, beta_ + 0.5 * h_ * b2, beta_rate_ + 0.5 * h_ * v2, b3, v3);
      accel(m0, m1, s1, M, beta_ + h_ * b3, beta_rate_ + h_ * v3, b4, v4);
      beta_ += h_ / 6.0 * (b1 + 2.0 * (b2 + b3) + b4);
      beta_rate_ += h_ / 6.0 * (v1 + 2.0 * (v2 + v3) + v4);
    }
    return beta_;
  }
  double update(const GyroCaseMotion& m, double M = 0.0) { return update(m, m, M); }

  double beta() const { return beta_; }            // output angle [rad]
  double beta_rate() const { return beta_rate_; }  // [rad/s]
  // The instrument's reading in input units: P (c2/H) β [rad/s]; I (d2/H) β [rad]; I² (B/H) β [rad s].
  double indicated() const {
    switch (p_.kind()) {
      case SingleAxisGyroKind::kRate: return p_.c2 / p_.H * beta_;
      case SingleAxisGyroKind::kIntegrating: return p_.d2 / p_.H * beta_;
      case SingleAxisGyroKind::kDoubleIntegrating: return p_.B / p_.H * beta_;
    }
    return 0.0;
  }

 private:
  // (β', β'') at fraction s of the sample.
  void accel(const GyroCaseMotion& m0, const GyroCaseMotion& m1, double s, double M, double beta,
             double beta_rate, double& dbeta, double& dbeta_rate) const {
    const double O1 = m0.Omega1 + s * (m1.Omega1 - m0.Omega1);
    const double O2d = m0.Omega2_dot + s * (m1.Omega2_dot - m0.Omega2_dot);
    const double O3 = m0.Omega3 + s * (m1.Omega3 - m0.Omega3);
    dbeta = beta_rate;
    dbeta_rate = (p_.H * O1 - p_.B * O2d + M - p_.d2 * beta_rate - (p_.c2 + p_.H * O3) * beta) / p_.B;
  }

  SingleAxisGyroParams p_;
  int n_{1};
  double h_{1e-3};
  double beta_{0.0};
  double beta_rate_{0.0};
};

}  // namespace gyrostab::sensors
