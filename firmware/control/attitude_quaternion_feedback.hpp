// Attitude loop by quaternion error feedback for a rigid spacecraft (docs/models/cmg-cluster.md#attitude-loop):
//   q_e = q_ref⁻¹ ⊗ q        (the attitude error, body axes; q = q_WB, q_ref the commanded q_WB)
//   u = −K_p q_e,vec sign(q_e,0) − K_d ω  (+ ω × H_total, the gyroscopic feed-forward)
// sign(q_e,0) takes the shorter way round (q and −q are the same attitude). For small errors q_e,vec ≈ θ/2,
// so per body axis k: J_k θ'' + K_d,k θ' + (K_p,k/2) θ = 0 (with the feed-forward cancelling ω × H, or for
// small rates). The scene sets K_p,k = 2 ω_a² J_k, K_d,k = 2 ζ ω_a J_k: natural frequency ω_a, damping ζ.
// The feed-forward uses H_total = J ω + h Σ s_i(δ_i) (the gimbal inertia's I_g ν g_i is left out: it is
// I_g ν_max ≪ h).
// Sampled (T the control period, sampled_loop_limits.hpp): K_d,k T/J_k ≤ 0.5 and sqrt(K_p,k/(2 J_k)) T ≤ 0.5;
// and the gimbal servos must be faster than the loop: the loop's fastest closed-loop rate
// (ζ + sqrt(ζ² − 1)) ω_a for ζ ≥ 1, ω_a otherwise, at most servo_bandwidth/4 (the servo's two poles at −ω_s
// then cost the loop at most about 2·atan(1/4) = 28° of phase).
// Also: quaternion_from_euler321 rebuilds q from the 3-2-1 angles (roll φ, pitch θ, yaw ψ) the sensors send.
// O(1), no heap. Tests: tests/oracle/cmg_cluster_test.cpp. Docs: docs/models/cmg-cluster.md#attitude-loop
#pragma once

#include <cmath>

#include "firmware/control/config_check.hpp"
#include "firmware/control/sampled_loop_limits.hpp"
#include "firmware/math/deterministic_math.hpp"

namespace gyrostab::firmware {

struct AttitudeQuaternion {
  double w{1.0}, x{0.0}, y{0.0}, z{0.0};
};

inline AttitudeQuaternion quaternion_multiply(const AttitudeQuaternion& a, const AttitudeQuaternion& b) {
  return {a.w * b.w - a.x * b.x - a.y * b.y - a.z * b.z, a.w * b.x + a.x * b.w + a.y * b.z - a.z * b.y,
          a.w * b.y - a.x * b.z + a.y * b.w + a.z * b.x, a.w * b.z + a.x * b.y - a.y * b.x + a.z * b.w};
}

// q = q_z(ψ) ⊗ q_y(θ) ⊗ q_x(φ) (3-2-1: yaw, then pitch, then roll).
inline AttitudeQuaternion quaternion_from_euler321(double roll, double pitch, double yaw) {
  const double cr = math::cos(0.5 * roll), sr = math::sin(0.5 * roll);
  const double cp = math::cos(0.5 * pitch), sp = math::sin(0.5 * pitch);
  const double cy = math::cos(0.5 * yaw), sy = math::sin(0.5 * yaw);
  return {cy * cp * cr + sy * sp * sr, cy * cp * sr - sy * sp * cr, cy * sp * cr + sy * cp * sr,
          sy * cp * cr - cy * sp * sr};
}

struct AttitudeGains {
  double J[3][3]{{60.0, 0, 0}, {0, 50.0, 0}, {0, 0, 40.0}};  // spacecraft inertia the law assumes [kg m²]
  double kp[3]{6.0, 5.0, 4.0};                               // K_p per body axis [N m]
  double kd[3]{24.0, 20.0, 16.0};                            // K_d per body axis [N m s/rad]
  bool gyroscopic_feedforward{true};                         // add ω × H_total
  double servo_bandwidth{40.0};                              // the gimbal servos' ω_s the loop relies on [rad/s]
};

struct AttitudeError {
  double vec[3]{};  // q_e,vec sign(q_e,0) [-]
};

inline AttitudeError attitude_error(const AttitudeQuaternion& q_ref, const AttitudeQuaternion& q) {
  const AttitudeQuaternion conj{q_ref.w, -q_ref.x, -q_ref.y, -q_ref.z};
  const AttitudeQuaternion e = quaternion_multiply(conj, q);
  const double sgn = e.w < 0.0 ? -1.0 : 1.0;
  AttitudeError out;
  out.vec[0] = sgn * e.x;
  out.vec[1] = sgn * e.y;
  out.vec[2] = sgn * e.z;
  return out;
}

// The torque demand u [N m] from the error, the body rate w [rad/s] and H_total [N m s] (body axes).
inline void attitude_torque(const AttitudeGains& g, const AttitudeError& e, const double* w, const double* H,
                            double* u) {
  for (int k = 0; k < 3; ++k) u[k] = -g.kp[k] * e.vec[k] - g.kd[k] * w[k];
  if (g.gyroscopic_feedforward) {
    u[0] += w[1] * H[2] - w[2] * H[1];
    u[1] += w[2] * H[0] - w[0] * H[2];
    u[2] += w[0] * H[1] - w[1] * H[0];
  }
}

// Start-up check for control period T [s]. O(1).
inline ConfigCheck check_attitude_gains(const AttitudeGains& g, double T) {
  for (int k = 0; k < 3; ++k) {
    const double Jk = g.J[k][k];
    if (!(std::isfinite(Jk) && Jk > 0.0)) return ConfigCheck::refused("attitude loop: J's diagonal must be > 0", Jk);
    if (!(std::isfinite(g.kp[k]) && g.kp[k] > 0.0 && std::isfinite(g.kd[k]) && g.kd[k] > 0.0)) {
      return ConfigCheck::refused("attitude loop: kp and kd must be finite and > 0", g.kp[k]);
    }
    const double kd_max = max_sampled_damping(Jk, T);
    if (!(g.kd[k] <= kd_max)) {
      return ConfigCheck::refused("attitude loop: kd T / J > 0.5, the sampled loop oscillates", g.kd[k], 0.0, kd_max);
    }
    const double kp_max = 2.0 * max_sampled_stiffness(Jk, T);
    if (!(g.kp[k] <= kp_max)) {
      return ConfigCheck::refused("attitude loop: sqrt(kp/(2J)) T > 0.5, the sampled loop is too stiff", g.kp[k],
                                  0.0, kp_max);
    }
    // The continuous loop J s² + kd s + kp/2: its fastest root against the servo bandwidth.
    const double wn = std::sqrt(0.5 * g.kp[k] / Jk);
    const double zeta = g.kd[k] / (2.0 * Jk * wn);
    const double fastest = zeta >= 1.0 ? (zeta + std::sqrt(zeta * zeta - 1.0)) * wn : wn;
    if (!(std::isfinite(g.servo_bandwidth) && fastest <= 0.25 * g.servo_bandwidth)) {
      return ConfigCheck::refused(
          "attitude loop: its fastest closed-loop rate exceeds servo_bandwidth/4 (the gimbal servos lag it)",
          fastest, 0.0, 0.25 * g.servo_bandwidth);
    }
  }
  return ConfigCheck::accepted();
}

}  // namespace gyrostab::firmware
