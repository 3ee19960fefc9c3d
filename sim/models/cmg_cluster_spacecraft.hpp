// A rigid spacecraft steered by a cluster of single-gimbal control moment gyros (CMGs): the gyrostat of
// Magnus §4.1 ((4.3)-(4.7): a carrier with rotors of constant spin momentum) whose rotor axes are turned by
// gimbal motors, the three-axis servo gyro of §14.4, (14.45) (M1 = −H β', M2 = H α': the gimbal rate turns the
// rotor's momentum and the carrier takes the reaction).
//
// Geometry: sim/models/cmg_geometry.hpp (gimbal axes g_i, spin axes s_i(δ_i), torque axes t_i = g_i × s_i).
// Total angular momentum about the centre of mass, body axes:
//   H = J ω + Σ I_g ν_i g_i + h Σ s_i(δ_i)                                   ν_i = δ_i'
// Balance of the whole (spacecraft + gimbals + rotors), body-frame derivative:
//   d/dt (J ω + Σ I_g ν_i g_i + h Σ s_i) + ω × H = T_ext                    (the gyrostat (4.3) with turning rotors)
//   J ω' + Σ I_g ν_i' g_i + Σ h ν_i t_i + ω × H = T_ext
// Each gimbal (gimbal + rotor) about its axis g_i, fixed in the body, driven by its motor torque τ_i:
//   I_g (g_i·ω' + ν_i') = τ_i + h ω·t_i        (h ω·t_i: the gyroscopic reaction of the carried rotor, (14.43))
// Eliminating ν_i' gives the carrier's rate with the gimbals free to turn:
//   (J − Σ I_g g_i g_iᵀ) ω' = T_ext − ω × H − Σ h ν_i t_i − Σ g_i (τ_i + h ω·t_i)
//   ν_i' = (τ_i + h ω·t_i)/I_g − g_i·ω'
// and d/dt(R H) = R T_ext exactly, whatever the motors do (their torques are internal); the energy
// E = ½ ωᵀJω + Σ I_g ν_i (g_i·ω) + ½ Σ I_g ν_i² obeys E' = ω·T_ext + Σ ν_i τ_i.
// The gimbal inertia terms are KEPT about the gimbal axes (I_g: the gimbal servo's load and the momentum
// I_g ν g_i it carries); the changes of the cluster's inertia with δ are NEGLECTED: J is constant, i.e. the
// gimbal-rotor units' transverse inertia is taken as if symmetric about g_i (their difference A^R − C^R
// times ν is small against h). The rotor's spin momentum h is held constant by its spin motor (the book's
// case (a) of §4.1, H^R = const); its spin energy is not in E.
//
// Gimbal drives (GimbalDriveMode):
//   kRateServo  the CMG electronics' rate servo: a continuous PI on the gimbal rate with the motor torque
//               limit, τ_i = clamp(k_p (ν_c,i − ν_i) + k_i ξ_i, ±τ_max) − b ν_i, ξ_i' = ν_c,i − ν_i (held
//               while the torque is clipped and the error pushes further: conditional integration);
//               k_p = 2 I_g ω_s, k_i = I_g ω_s²: both poles at −ω_s on the bare gimbal (the servo bandwidth).
//   kTorque     the held motor torques τ_i (inputs) − b ν_i.
//   kLocked     gimbals clamped to the body (ν ≡ 0): the free gyrostat of §4.1 when T_ext = 0.
//
// State x (kStateSize = 19, unused CMG slots stay 0):
//   [ ω (3) rad/s, body | q_WB (x, y, z, w) (4) | δ (4) rad | ν = δ' (4) rad/s | ξ (4) rad (servo integrals) ]
// Parameters (SI): J spacecraft inertia tensor incl. the CMG units, body axes, about the centre of mass
// [kg m²]; h rotor spin momentum of each CMG [N m s]; I_g gimbal + rotor inertia about the gimbal axis
// [kg m²]; ω_s servo bandwidth [rad/s]; τ_max gimbal motor torque limit [N m]; b gimbal bearing viscous
// friction [N m s/rad].
// Inputs (zero-order hold): ν_c gimbal rate commands [rad/s]; τ motor torques [N m] (kTorque); T_ext [N m].
// Oracle: tests/oracle/cmg_cluster_test.cpp (momentum and energy conservation, the free gyrostat's nutation
// (4.8)-(4.13), the envelope, the steering laws at the singular configuration, a slew).
// Docs: docs/models/cmg-cluster.md
#pragma once

#include <Eigen/Core>
#include <Eigen/Cholesky>
#include <cmath>

#include "sim/models/cmg_geometry.hpp"
#include "sim/dynamics/quaternion.hpp"

namespace gyrostab::models {

enum class GimbalDriveMode { kRateServo, kTorque, kLocked };

struct CmgClusterParams {
  Eigen::Matrix3d J{Eigen::Vector3d(60.0, 50.0, 40.0).asDiagonal()};  // spacecraft + CMG units [kg m²]
  CmgGeometry geometry{pyramid_geometry()};
  double h{5.0};                  // rotor spin momentum, each CMG [N m s]
  double gimbal_inertia{0.02};    // I_g: gimbal + rotor about the gimbal axis [kg m²]
  double servo_bandwidth{40.0};   // ω_s: the rate servo's poles at −ω_s [rad/s]
  double torque_limit{2.0};       // τ_max: gimbal motor torque limit [N m]
  double gimbal_friction{0.0};    // b: viscous friction in each gimbal bearing [N m s/rad]
  GimbalDriveMode drive{GimbalDriveMode::kRateServo};

  double servo_kp() const { return 2.0 * gimbal_inertia * servo_bandwidth; }             // [N m s/rad]
  double servo_ki() const { return gimbal_inertia * servo_bandwidth * servo_bandwidth; }  // [N m/rad]

  // J − Σ I_g g_i g_iᵀ: the carrier's inertia with the gimbals free to turn [kg m²].
  Eigen::Matrix3d free_gimbal_inertia() const {
    Eigen::Matrix3d Js = J;
    for (int i = 0; i < geometry.count; ++i) {
      Js -= gimbal_inertia * geometry.gimbal_axis[i] * geometry.gimbal_axis[i].transpose();
    }
    return Js;
  }

  // nullptr if physically possible, else the reason (scene validation).
  const char* invalid_reason() const {
    if (const char* e = geometry.invalid_reason()) return e;
    if (!J.allFinite() || (J - J.transpose()).norm() > 1e-12 * J.norm()) return "J must be symmetric and finite";
    if (Eigen::LLT<Eigen::Matrix3d>(J).info() != Eigen::Success) return "J must be positive definite";
    // The principal moments satisfy the triangle inequality (1.10) iff the second-moment tensor
    // ∫ r rᵀ dm = ½ tr(J) 1 − J is positive semi-definite.
    const Eigen::Matrix3d P = 0.5 * J.trace() * Eigen::Matrix3d::Identity() - J;
    const Eigen::LDLT<Eigen::Matrix3d> ldlt(P);
    if (ldlt.info() != Eigen::Success || ldlt.vectorD().minCoeff() < -1e-12 * J.trace()) {
      return "J's principal moments must satisfy the triangle inequality";
    }
    if (!(h > 0.0) || !std::isfinite(h)) return "h must be > 0";
    if (!(gimbal_inertia > 0.0)) return "the gimbal inertia must be > 0";
    if (Eigen::LLT<Eigen::Matrix3d>(free_gimbal_inertia()).info() != Eigen::Success) {
      return "J − Σ I_g g gᵀ must be positive definite (the gimbal inertia is part of J)";
    }
    if (!(servo_bandwidth > 0.0) || !(torque_limit > 0.0) || !(gimbal_friction >= 0.0)) {
      return "servo bandwidth and torque limit must be > 0, friction >= 0";
    }
    return nullptr;
  }
};

struct CmgClusterInputs {
  double rate_command[kMaxCmgs]{};   // ν_c [rad/s] (kRateServo)
  double motor_torque[kMaxCmgs]{};   // τ [N m] (kTorque)
  dynamics::Vec3 external_torque{dynamics::Vec3::Zero()};  // T_ext, body axes [N m]
};

class CmgClusterSpacecraft {
 public:
  static constexpr int kStateSize = 19;
  using State = Eigen::Matrix<double, kStateSize, 1>;
  static constexpr const char* kName = "cmg-cluster";
  // The state's blocks, by name (first index of each).
  static constexpr int kOmega = 0, kQuat = 3, kDelta = 7, kGimbalRate = 11, kServoIntegral = 15;

  explicit CmgClusterSpacecraft(const CmgClusterParams& p = {})
      : p_(p),
        J_inv_(p.J.inverse()),
        Js_inv_(p.free_gimbal_inertia().inverse()),
        kp_(p.servo_kp()),
        ki_(p.servo_ki()) {}

  mutable CmgClusterInputs inputs{};  // held between steps

  const CmgClusterParams& params() const { return p_; }

  static State make_state(const dynamics::Vec3& w, const dynamics::Quat& q, const double* delta = nullptr) {
    State x = State::Zero();
    x.segment<3>(kOmega) = w;
    x.segment<4>(kQuat) = q.normalized().coeffs();
    if (delta != nullptr) {
      for (int i = 0; i < kMaxCmgs; ++i) x[kDelta + i] = delta[i];
    }
    return x;
  }

  // The motor torque of gimbal i at state x (before the bearing friction) [N m], and whether it is clipped.
  double motor_torque(const State& x, int i, bool* clipped = nullptr) const {
    if (p_.drive == GimbalDriveMode::kTorque) {
      if (clipped != nullptr) *clipped = false;
      return inputs.motor_torque[i];
    }
    const double raw = kp_ * (inputs.rate_command[i] - x[kGimbalRate + i]) + ki_ * x[kServoIntegral + i];
    const double out = std::fmax(-p_.torque_limit, std::fmin(p_.torque_limit, raw));
    if (clipped != nullptr) *clipped = out != raw;
    return out;
  }

  void derivative(double /*t*/, const State& x, State& dx) const {
    const int n = p_.geometry.count;
    const dynamics::Vec3 w = x.segment<3>(kOmega);
    dx.setZero();
    dynamics::Vec3 H = p_.J * w;
    dynamics::Vec3 t[kMaxCmgs];
    for (int i = 0; i < n; ++i) {
      const double d = x[kDelta + i];
      H += p_.h * p_.geometry.spin_axis(i, d) + p_.gimbal_inertia * x[kGimbalRate + i] * p_.geometry.gimbal_axis[i];
      t[i] = p_.geometry.torque_axis(i, d);
    }
    dynamics::quaternion_rate(x.segment<4>(kQuat), w, dx.segment<4>(kQuat));
    if (p_.drive == GimbalDriveMode::kLocked) {
      dx.segment<3>(kOmega) = J_inv_ * (inputs.external_torque - w.cross(H));
      return;
    }
    dynamics::Vec3 rhs = inputs.external_torque - w.cross(H);
    double gimbal_torque[kMaxCmgs];
    for (int i = 0; i < n; ++i) {
      const double nu = x[kGimbalRate + i];
      bool clipped = false;
      const double tau = motor_torque(x, i, &clipped);
      gimbal_torque[i] = tau - p_.gimbal_friction * nu + p_.h * w.dot(t[i]);
      rhs -= p_.h * nu * t[i] + gimbal_torque[i] * p_.geometry.gimbal_axis[i];
      if (p_.drive == GimbalDriveMode::kRateServo) {
        const double e = inputs.rate_command[i] - nu;
        dx[kServoIntegral + i] = clipped && (e > 0.0) == (tau > 0.0) ? 0.0 : e;
      }
    }
    const dynamics::Vec3 wdot = Js_inv_ * rhs;
    dx.segment<3>(kOmega) = wdot;
    for (int i = 0; i < n; ++i) {
      dx[kDelta + i] = x[kGimbalRate + i];
      dx[kGimbalRate + i] = gimbal_torque[i] / p_.gimbal_inertia - p_.geometry.gimbal_axis[i].dot(wdot);
    }
  }
  void project(State& x) const { dynamics::renormalize_cheap(x.segment<4>(kQuat)); }

  // H in body axes [N m s].
  dynamics::Vec3 momentum_body(const State& x) const {
    dynamics::Vec3 H = p_.J * x.segment<3>(kOmega);
    for (int i = 0; i < p_.geometry.count; ++i) {
      H += p_.h * p_.geometry.spin_axis(i, x[kDelta + i]) +
           p_.gimbal_inertia * x[kGimbalRate + i] * p_.geometry.gimbal_axis[i];
    }
    return H;
  }
  // The rotors' momentum h Σ s_i in body axes [N m s].
  dynamics::Vec3 cmg_momentum_body(const State& x) const {
    return p_.h * p_.geometry.unit_momentum(x.data() + kDelta);
  }
  // H in inertial axes: conserved without T_ext [N m s].
  dynamics::Vec3 momentum_world(const State& x) const {
    const Eigen::Map<const dynamics::Quat> q(x.data() + kQuat);
    return q * momentum_body(x);
  }
  // E = ½ ωᵀJω + Σ I_g ν_i (g_i·ω) + ½ Σ I_g ν_i² [J]: E' = ω·T_ext + Σ ν_i τ_i.
  double energy(const State& x) const {
    const dynamics::Vec3 w = x.segment<3>(kOmega);
    double E = 0.5 * w.dot(p_.J * w);
    for (int i = 0; i < p_.geometry.count; ++i) {
      const double nu = x[kGimbalRate + i];
      E += p_.gimbal_inertia * nu * (p_.geometry.gimbal_axis[i].dot(w) + 0.5 * nu);
    }
    return E;
  }
  double singularity_measure(const State& x) const { return p_.geometry.singularity_measure(x.data() + kDelta); }

 private:
  CmgClusterParams p_;
  Eigen::Matrix3d J_inv_, Js_inv_;
  double kp_, ki_;
};

}  // namespace gyrostab::models
