// A platform turning about its axis 3 on a base with angular vibration, driven by a geared servo motor and
// carrying a single-degree-of-freedom rate gyro (P or I) whose input axis is the platform's axis 3: the plant
// of the coning device (Magnus §15.5, (15.36)-(15.42); the gyro: sim/sensors/single_axis_gyro_coning.hpp).
// The firmware slaves the platform so that the gyro's reading is zero; with the gyro's coning error
// ω̄_err the platform then turns at −ω̄_err (docs/models/coning.md).
//
// Base: yaw ψ_b = Φ cos δ sin νt about base axis 3, roll φ_b = Φ sin δ sin(νt − ε) about base axis 1
// (motion::PrescribedBaseRotation: R = Rz(ψ_b) Rx(φ_b)), so ω_b = (φ_b', ψ_b' sin φ_b, ψ_b' cos φ_b): a
// vibration of amplitude Φ about an axis at δ from axis 3 towards axis 1, planar for ε = 0, conical
// (elliptic) otherwise. The base's attitude is periodic: it has no mean rotation. Or the base motion a scene's
// [motion] block chooses (motion::SceneBaseMotion: prescribed yaw/pitch/roll, or a recorded motion), of which
// only ω_b and ω_b' act (the platform reads no specific force).
// Platform: turned by φ about the common axis 3 relative to the base; its rate in platform axes
//   ω_p = (cφ ω_b1 + sφ ω_b2, −sφ ω_b1 + cφ ω_b2, ω_b3 + φ')
//   ω_p' = (cφ ω_b1' + sφ ω_b2' + φ' ω_p2, −sφ ω_b1' + cφ ω_b2' − φ' ω_p1, ω_b3' + φ'')   (component derivatives)
// Drive: a geared DC servo with its own speed loop: τ_d φ'' + φ' = K_v V. The gear is stiff and the motor's
// reflected inertia dominates the platform's, so the base's vibration does not move the platform relative
// to the base: the platform follows the base's yaw at ν and the gyro sees it (a platform on a free bearing
// would stay inertially still about axis 3, and its gyro would see no vibration about its input axis).
// Gyro on the platform: input axis 1 = platform 3, spin axis 3 = platform 1, output axis 2 = −platform 2:
//   Ω_gyro = (ω_p3, −ω_p2, ω_p1), Ω_gyro' likewise; β'' from (1) of single_axis_gyro_coning.hpp.
//
// State [φ (rad), φ' (rad/s), β (rad), β' (rad/s)]. Input: the drive voltage V [V], held per tick.
// Parameters: the gyro (B [kg m²], d2 [N m s/rad], c2 [N m/rad], H [N m s], A_g − C_g [kg m²]); τ_d [s],
// K_v [rad/s/V]; Φ [rad], ν [rad/s], δ [rad], ε [rad].
// Assumptions: rigid platform and gear; no friction, no backlash; the base's centre of rotation fixed.
// Oracle: tests/oracle/coning_test.cpp (the closed loop against the open-loop coning rate).
// Docs: docs/models/coning.md#the-coning-platform
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <numbers>

#include "sim/motion/prescribed_base_rotation.hpp"
#include "sim/motion/scene_base_motion.hpp"
#include "sim/sensors/single_axis_gyro_coning.hpp"

namespace gyrostab::models {

struct ConingPlatformParams {
  sensors::ConingGyroParams gyro{};       // sample_period and substeps unused (the plant's step applies)
  double drive_time_constant{0.005};     // τ_d [s]
  double drive_rate_per_volt{0.1};       // K_v [rad/s per V]
  double amplitude{0.01};                // Φ [rad]
  double frequency{2.0 * std::numbers::pi * 5.0};  // ν [rad/s]
  double direction{0.25 * std::numbers::pi};       // δ, from platform axis 3 (gyro input) towards 1 (spin) [rad]
  double phase{0.0};                     // ε, lag of the spin-axis component [rad]

  // The vibration's amplitudes about the gyro's input and spin axes [rad/s].
  double Omega10() const { return amplitude * frequency * std::cos(direction); }
  double Omega30() const { return amplitude * frequency * std::sin(direction); }

  motion::PrescribedBaseRotation<1> base() const {
    motion::PrescribedBaseRotation<1> b;
    b.yaw.harmonics[0] = {amplitude * std::cos(direction), frequency, 0.0};
    b.yaw.count = 1;
    b.roll.harmonics[0] = {amplitude * std::sin(direction), frequency, -phase};
    b.roll.count = 1;
    return b;
  }
};

class ConingPlatform {
 public:
  static constexpr int kStateSize = 4;
  using State = Eigen::Matrix<double, 4, 1>;
  static constexpr const char* kName = "coning-platform";
  static constexpr int kPhi = 0, kPhiRate = 1, kBeta = 2, kBetaRate = 3;

  struct Inputs {
    double voltage{0.0};  // V [V]
  };

  explicit ConingPlatform(const ConingPlatformParams& p = {}) : p_(p), base_(generated(p)) {}
  // The base moved by `base` instead (a scene's [motion]: prescribed or recorded; only ω_B, ω̇_B act).
  ConingPlatform(const ConingPlatformParams& p, const motion::SceneBaseMotion& base) : p_(p), base_(base) {}

  // The parameters' vibration as a scene base motion (the same bits as PrescribedBaseRotation alone).
  static motion::SceneBaseMotion generated(const ConingPlatformParams& p) {
    motion::SceneBaseMotion m;
    m.kind = motion::BaseMotionKind::kPrescribed;
    m.prescribed = p.base();
    return m;
  }

  Inputs inputs{};  // held between steps

  const ConingPlatformParams& params() const { return p_; }

  static State make_state(double phi, double phi_rate, double beta, double beta_rate) {
    State x;
    x << phi, phi_rate, beta, beta_rate;
    return x;
  }

  double phi_accel(const State& x) const {
    return (p_.drive_rate_per_volt * inputs.voltage - x[kPhiRate]) / p_.drive_time_constant;
  }

  // The platform's absolute angular velocity and its derivative, platform axes.
  void platform_rates(double t, const State& x, dynamics::Vec3& w, dynamics::Vec3& dw) const {
    const models::BaseSample b = base_(t);
    const double s = std::sin(x[kPhi]), c = std::cos(x[kPhi]), r = x[kPhiRate];
    w = {c * b.w_B[0] + s * b.w_B[1], -s * b.w_B[0] + c * b.w_B[1], b.w_B[2] + r};
    dw = {c * b.dw_B[0] + s * b.dw_B[1] + r * w[1], -s * b.dw_B[0] + c * b.dw_B[1] - r * w[0],
          b.dw_B[2] + phi_accel(x)};
  }

  sensors::GyroCaseRates gyro_case_rates(double t, const State& x) const {
    dynamics::Vec3 w, dw;
    platform_rates(t, x, w, dw);
    return {{w[2], -w[1], w[0]}, {dw[2], -dw[1], dw[0]}};
  }

  void derivative(double t, const State& x, State& dx) const {
    dx[kPhi] = x[kPhiRate];
    dx[kPhiRate] = phi_accel(x);
    dx[kBeta] = x[kBetaRate];
    dx[kBetaRate] = sensors::coning_gyro_accel(p_.gyro, x[kBeta], x[kBetaRate], gyro_case_rates(t, x));
  }
  void project(State&) const {}

  const motion::SceneBaseMotion& base() const { return base_; }

 private:
  ConingPlatformParams p_;
  motion::SceneBaseMotion base_;
};

}  // namespace gyrostab::models
