// Single-degree-of-freedom gyro (P: spring c2 and damper d2; I: c2 = 0) driven by the full angular velocity
// of its case, with the exact kinematics of the gimbal: the gimbal turns by β about the output axis, so the
// axis the rotor senses — the effective input axis, perpendicular to the output axis and the rotor — tilts by
// β away from the case's input axis towards its spin axis. Under angular vibration with components about
// both the input and the spin axis, the product of that tilt and the rate about the spin axis has a mean:
// the coning (rectification) error of Magnus §15.5, (15.36)-(15.42). Any device can use it; the coning
// platform (sim/models/coning_platform.hpp) does.
//
// Frames: case axes 1 input, 2 output, 3 spin (at β = 0), right-handed; the gimbal turns by β about 2, so
// its axes are 1' = cosβ e1 − sinβ e3 (effective input axis), 2, 3' = sinβ e1 + cosβ e3 (rotor axis; β > 0
// turns the rotor towards the input axis, the book's "like-directed parallelism").
// Gimbal rates about 1' and 3':  ω1' = Ω1 cosβ − Ω3 sinβ,   ω3' = Ω1 sinβ + Ω3 cosβ.
// Euler's equation of gimbal + rotor about the output axis 2 (angular momentum (A_g ω1', B(Ω2 + β'),
// C_g ω3' + H) in gimbal axes, H held by the spin motor):
//   B (β'' + Ω2') = H ω1' − (A_g − C_g) ω1' ω3' − c2 β − d2 β' + M                                   (1)
// Linearized in β this is Magnus (15.1) with c1 → ∞:  B β'' + d2 β' + (c2 + H Ω3) β = H Ω1 − B Ω2'; the
// term −H Ω3 β is the tilt of the effective input axis, the source of the coning error.
// Indicated quantity (the instrument's reading in input units): P-gyro (c2 > 0) the rate (c2/H) β [rad/s]
// (15.4); I-gyro (c2 = 0, d2 > 0) the angle (d2/H) β [rad] (15.16), whose rate is (d2/H) β'.
// Coning error to first order (second order in the vibration, derived in docs/models/coning.md): with
// Ω1 = Ω10 cos νt on the input axis and Ω3 = Ω30 cos(νt − ε) on the spin axis, the mean indicated rate is
//   −½ Ω10 Ω30 [Re(G(iν) e^{iε}) + (A_g − C_g) cos ε / H],   G(s) = H / (B s² + d2 s + c2)
// (sim/oracles/coning_closed_forms.hpp): P quasi-static, ε = 0: −H Ω10 Ω30 / (2 c2) (15.39)-(15.41);
// ideal I (B → 0): −H Ω10 Ω30 sin ε / (2 d2 ν), zero for planar vibration (15.42).
//
// State [β (rad), β' (rad/s)]. Parameters (SI): SingleAxisGyroParams B [kg m²], d2 [N m s/rad], c2 [N m/rad],
// H [N m s], T [s], RK4 sub-steps per sample (0: h |λ|max ≤ 0.05 as in rate_integrating_gyro.hpp);
// inertia_difference A_g − C_g [kg m²] of gimbal + rotor about 1' and 3' (the rotor's spin momentum excluded;
// 0: the anisoinertia torque vanishes and only the kinematic coning remains).
// Inputs: the case angular velocity Ω [rad/s] and its derivative Ω' [rad/s²] (derivative of the case-axis
// components), as a callable t ↦ GyroCaseRates; a torquer M [N m] held per sample.
// Assumptions: symmetric rotor at constant H; rigid gimbal bearings (c1 → ∞: no outer-axis freedom); no
// friction, no unbalance, no anisoelasticity; β unrestricted (the trigonometric terms are exact).
// Oracle: tests/oracle/coning_test.cpp — (15.39)-(15.41) for the P-gyro, no error for Ω along the output
// axis, (15.42) and the conical error of the I-gyro, the anisoinertia term.
// Hot path: allocation-free, O(sub-steps) per sample, 2 sin/cos per derivative.
// Docs: docs/models/coning.md#the-gyro-with-its-gimbal-kinematics
#pragma once

#include <cmath>

#include "sim/dynamics/quaternion.hpp"
#include "sim/sensors/rate_integrating_gyro.hpp"

namespace gyrostab::sensors {

struct ConingGyroParams {
  SingleAxisGyroParams gyro{};   // B, d2, c2, H, sample period, sub-steps
  double inertia_difference{0.0};  // A_g − C_g [kg m²]

  const char* invalid_reason() const {
    if (const char* why = gyro.invalid_reason()) return why;
    if (!std::isfinite(inertia_difference)) return "inertia_difference must be finite";
    if (gyro.kind() == SingleAxisGyroKind::kDoubleIntegrating) return "c2 = d2 = 0 (I²-gyro) is not modelled here";
    return nullptr;
  }
};

// The case's angular motion at one instant, case axes (1 input, 2 output, 3 spin).
struct GyroCaseRates {
  dynamics::Vec3 Omega{dynamics::Vec3::Zero()};      // Ω [rad/s]
  dynamics::Vec3 Omega_dot{dynamics::Vec3::Zero()};  // Ω' [rad/s²]
};

// β'' of (1) [rad/s²].
inline double coning_gyro_accel(const ConingGyroParams& p, double beta, double beta_rate, const GyroCaseRates& m,
                                double M = 0.0) {
  const double sb = std::sin(beta), cb = std::cos(beta);
  const double w1 = m.Omega[0] * cb - m.Omega[2] * sb;  // about the effective input axis 1'
  const double w3 = m.Omega[0] * sb + m.Omega[2] * cb;  // about the rotor axis 3'
  const SingleAxisGyroParams& g = p.gyro;
  return (g.H * w1 - p.inertia_difference * w1 * w3 - g.c2 * beta - g.d2 * beta_rate + M) / g.B - m.Omega_dot[1];
}

// The effective input axis 1' in case axes [-].
inline dynamics::Vec3 effective_input_axis(double beta) { return {std::cos(beta), 0.0, -std::sin(beta)}; }

// The reading in input units: P (c2/H) β [rad/s], I (d2/H) β [rad].
inline double coning_gyro_indicated(const ConingGyroParams& p, double beta) {
  const SingleAxisGyroParams& g = p.gyro;
  return g.kind() == SingleAxisGyroKind::kRate ? g.c2 / g.H * beta : g.d2 / g.H * beta;
}

// The gyro alone on a case whose motion is a given function of time: RK4 with sub-steps, motion sampled at
// the stages.
class ConingGyro {
 public:
  explicit ConingGyro(const ConingGyroParams& p) : p_(p) {
    // The fastest rate of the linear part at Ω3 = 0 (the spin-axis stiffening H Ω3 is small against c2 or d2/B
    // for the vibrations this model is for).
    const double h_target = 0.05 / SingleAxisGyro::fastest_rate(p.gyro, 0.0);
    n_ = p.gyro.substeps > 0 ? p.gyro.substeps
                             : static_cast<int>(std::ceil(p.gyro.sample_period / h_target - 1e-9));
    if (n_ < 1) n_ = 1;
    h_ = p.gyro.sample_period / n_;
  }

  const ConingGyroParams& params() const { return p_; }
  int substeps() const { return n_; }
  double substep() const { return h_; }

  void reset(double beta = 0.0, double beta_rate = 0.0) {
    beta_ = beta;
    beta_rate_ = beta_rate;
  }

  // Integrates [t0, t0 + T] with the case motion motion(t) (t ↦ GyroCaseRates) and the torquer M held.
  template <class Motion>
  double update(const Motion& motion, double t0, double M = 0.0) {
    for (int k = 0; k < n_; ++k) {
      const double t = t0 + k * h_;
      const GyroCaseRates m0 = motion(t), mh = motion(t + 0.5 * h_), m1 = motion(t + h_);
      const double b1 = beta_rate_, v1 = coning_gyro_accel(p_, beta_, beta_rate_, m0, M);
      const double b2 = beta_rate_ + 0.5 * h_ * v1;
      const double v2 = coning_gyro_accel(p_, beta_ + 0.5 * h_ * b1, b2, mh, M);
      const double b3 = beta_rate_ + 0.5 * h_ * v2;
      const double v3 = coning_gyro_accel(p_, beta_ + 0.5 * h_ * b2, b3, mh, M);
      const double b4 = beta_rate_ + h_ * v3;
      const double v4 = coning_gyro_accel(p_, beta_ + h_ * b3, b4, m1, M);
      beta_ += h_ / 6.0 * (b1 + 2.0 * (b2 + b3) + b4);
      beta_rate_ += h_ / 6.0 * (v1 + 2.0 * (v2 + v3) + v4);
    }
    return beta_;
  }

  double beta() const { return beta_; }            // [rad]
  double beta_rate() const { return beta_rate_; }  // [rad/s]
  double indicated() const { return coning_gyro_indicated(p_, beta_); }
  // The rate of the reading: P (c2/H) β [rad/s]; I (d2/H) β' [rad/s].
  double indicated_rate() const {
    const SingleAxisGyroParams& g = p_.gyro;
    return g.kind() == SingleAxisGyroKind::kRate ? g.c2 / g.H * beta_ : g.d2 / g.H * beta_rate_;
  }

 private:
  ConingGyroParams p_;
  int n_{1};
  double h_{1e-3};
  double beta_{0.0};
  double beta_rate_{0.0};
};

}  // namespace gyrostab::sensors
