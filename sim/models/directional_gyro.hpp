// Directional (heading) gyro: a rotor with its axis horizontal in a two-gimbal suspension whose outer gimbal
// axis is the vehicle's normal axis (the measuring axis: the outer-gimbal angle against the case is the
// heading indication), torqued about both gimbal axes by the corrections of the firmware
// (firmware/control/directional_gyro_corrections.hpp), on a case that rotates as the vehicle does.
//
// Book: Magnus §12.2 (docs/models/directional-gyro.md): apparent drift (12.21)-(12.22), heading correction
// (12.23), inter-gimbal correction (12.24), turn error (12.25)-(12.34); the gimbal chain and the case axes
// of §12.1 (the "321" heading gyro, (12.11)-(12.15)); the rotating frame of §10.2 (10.21)-(10.23).
// Case axes (the gimbals' base): 1 = the vehicle's normal axis, pointing up out of the roof (the outer gimbal
// axis), 2 = the right wing, 3 = forward. α = outer-gimbal angle about case axis 1, β = inner-gimbal angle
// about the outer gimbal's axis 2 (Cardan angles, §1.4.3c, as sim/models/gimbal_gyro.hpp); the rotor axis is
//   e = Rx(α) Ry(β) e3 = (sin β, −sin α cos β, cos α cos β)       (case axes; α = β = 0: rotor forward)
// so a rotor fixed in space reads α = ψ − A_r (ψ the heading, A_r the rotor's azimuth, both clockwise from
// north) on a level case: the indication is α plus the card's setting.
//
// Precession ("technical") theory, with the gimbal kinematics EXACT. The rotor's angular momentum is H e
// (gimbal inertia and nutation neglected, H constant: the book's §12.2 setting), so H e' = T, with T the
// torque the gimbals pass to the rotor: T·n = M1 (outer axis n = case axis 1), T·j = M2 (inner axis
// j = Rx(α) e2), T·e = 0 (the spin motor holds H). With m = j × e = (cos β, sin α sin β, −cos α sin β),
// det[n, j, e] = cos β gives T = M2 j + (M1/cos β) m. Relative to the case, which turns at ω (its absolute
// angular velocity, case axes), e's case components move by e' − ω × e = −α' cos β j + β' m, hence
//   α' = −(M2/H + ω·m)/cos β,        β' = M1/(H cos β) − ω·j                                   (exact)
// On a fixed base this is (10.20) (−H cos β α' = M2, H cos β β' = M1); linearized in α, β it is the
// precession form of (10.22) (α' = −M2/H − Ω1 + Ω3 β, β' = M1/H − Ω2 − Ω3 α). Nothing is linearized here:
// the vehicle's bank and pitch go through the gimbals exactly, so the kinematic term β^K ≈ −φ0 sin ψ of
// (12.25) and the gimbal error (12.13)-(12.14) come out of the kinematics, and so does the book's "indirect"
// error of the horizontal Earth rate (it tilts the inner gimbal; the inter-gimbal correction holds it).
// State x = [α (rad), β (rad)], α unwrapped (the outer gimbal turns freely through 360°).
// Parameters: H [N m s]. Inputs: the case rate ω(t) (rad/s, case axes, linear over the step), torquer
// commands M1 about the outer axis, M2 about the inner axis [N m] (zero-order hold).
// Assumptions: the book's — symmetric rotor at constant spin, massless gimbals (no nutation, no inertia
// torques A Ω', B Ω'), balanced rotor (no pendulous torque), no bearing friction, no random drift torque.
// Singular at gimbal lock, |β| = 90° (cos β = 0: the gimbals fold, Magnus (10.8)); the plant guards it.
// Oracle: tests/oracle/directional_gyro_test.cpp — apparent drift (12.21)-(12.22) and its compensation,
// the turn error β (12.25)+(12.29) and the azimuth drift δ (the corrected (12.32)) with the limits
// (12.33)-(12.34) and the φ0³/φ0⁴ scaling of the neglected terms, the heading correction's exponential.
// Docs: docs/models/directional-gyro.md
#pragma once

#include <cmath>

#include "sim/dynamics/quaternion.hpp"

namespace gyrostab::models {

struct DirectionalGyroParams {
  double H{0.1};  // spin angular momentum [N m s]

  // nullptr if usable, else why not (scene validation).
  const char* invalid_reason() const {
    if (!(std::isfinite(H) && H > 0.0)) return "H must be finite and > 0";
    return nullptr;
  }
};

// The case's absolute angular velocity over one step, case axes: linear between the step's ends.
struct CaseRateInputs {
  double t0{0.0};  // [s]
  double h{0.0};   // [s]; 0: hold w0
  dynamics::Vec3 w0{dynamics::Vec3::Zero()}, w1{dynamics::Vec3::Zero()};  // [rad/s]

  void hold(const dynamics::Vec3& w) {
    w0 = w;
    w1 = w;
    h = 0.0;
  }
  dynamics::Vec3 at(double t) const {
    if (!(h > 0.0)) return w0;
    return w0 + ((t - t0) / h) * (w1 - w0);
  }
};

struct DirectionalGyroInputs {
  CaseRateInputs case_rate{};
  double M1{0.0};  // torquer about the outer (normal) axis: inter-gimbal correction [N m]
  double M2{0.0};  // torquer about the inner axis: drift compensation + heading correction [N m]
};

// The rotor axis in case axes.
inline dynamics::Vec3 directional_gyro_rotor_axis(double alpha, double beta) {
  const double sa = std::sin(alpha), ca = std::cos(alpha), sb = std::sin(beta), cb = std::cos(beta);
  return {sb, -sa * cb, ca * cb};
}

// The gimbal angles that put the rotor along the unit vector e (case axes): β ∈ [−π/2, π/2],
// α ∈ (−π, π], the branch with cos β ≥ 0.
inline void directional_gyro_angles_of(const dynamics::Vec3& e, double& alpha, double& beta) {
  beta = std::asin(std::fmax(-1.0, std::fmin(1.0, e.x())));
  alpha = std::atan2(-e.y(), e.z());
}

// (α', β') of the exact precession theory (model header) [rad/s]. O(1).
inline void directional_gyro_rates(double H, const dynamics::Vec3& w, double alpha, double beta, double M1,
                                   double M2, double& alpha_rate, double& beta_rate) {
  const double sa = std::sin(alpha), ca = std::cos(alpha), sb = std::sin(beta), cb = std::cos(beta);
  const double w_m = w.x() * cb + w.y() * sa * sb - w.z() * ca * sb;  // ω·m
  const double w_j = w.y() * ca + w.z() * sa;                          // ω·j
  alpha_rate = -(M2 / H + w_m) / cb;
  beta_rate = M1 / (H * cb) - w_j;
}

class DirectionalGyro {
 public:
  static constexpr int kStateSize = 2;
  using State = Eigen::Matrix<double, 2, 1>;
  // The state's components, by name.
  static constexpr int kAlpha = 0, kBeta = 1;

  explicit DirectionalGyro(const DirectionalGyroParams& p = {}) : p_(p) {}

  DirectionalGyroInputs inputs{};  // held between steps

  const DirectionalGyroParams& params() const { return p_; }

  static State make_state(double alpha, double beta) {
    State x;
    x << alpha, beta;
    return x;
  }

  void derivative(double t, const State& x, State& dx) const {
    directional_gyro_rates(p_.H, inputs.case_rate.at(t), x[kAlpha], x[kBeta], inputs.M1, inputs.M2, dx[kAlpha],
                           dx[kBeta]);
  }
  void project(State&) const {}

 private:
  DirectionalGyroParams p_;
};

}  // namespace gyrostab::models
