// Servo gyro / control moment gyro drive (Magnus §14.4, docs/models/servo-gyro.md): the motor on the inner
// axis 2 holds the gimbal rate β' at a reference Ω, and the gyroscopic reaction puts a torque on axis 1.
//
// Book: (14.41)  A α'' + H cosβ β' = M1,     B β'' − H cosβ α' = M2
//       (14.42)  β' = Ω:  torque on axis 1  M1^KR = −H cosβ β' = −H Ω cos Ωt
//       (14.43)  the motor must overcome  M2^K = −H cosβ α'
//       (14.44)  torque amplification (M1^KR)max / (M2^K)max = 1/α_A
// Rate loop: the discrete PI of firmware/control/drive_loops.hpp (pi_step, back-calculation anti-windup
// with T_t = T: while the output is clipped the integral tracks the limit, so there is no windup and the
// output leaves the limit at most one tick after the error changes sign), with the feed-forward of (14.43):
//   e = Ω − β',   M2 = clamp(k_p e + I − H cosβ α' (if feedforward), ±torque_limit_Nm),
//   I ← I + k_i T e + (M2 − unclipped M2)                (T = control period)
// With the feed-forward the loop sees the plain inertia B β'' = M2 + (error of the feed-forward), so
// k_p = B ω_c gives a rate bandwidth ω_c and k_i = k_p ω_c / 4 a double closed-loop pole at −ω_c/2
// (s² + ω_c s + ω_c²/4); defaults (the plant's sim/models/servo_gyro.hpp: B = 0.5, H = 1): ω_c = 200 rad/s
// → k_p = 100 N m s/rad, k_i = 5000 N m/rad.
// Torque demand instead of a rate: to make the gyro put M1_demand on axis 1, Ω = −M1_demand / (H cosβ)
// (from (14.42)); near gimbal lock (|cosβ| → 0) the gyroscopic torque vanishes, so |cosβ| is floored at
// cos_beta_floor (kGimbalLockGuard): the demand is then only partly delivered, never by an unbounded rate.
// Signals (the servo gyro's table, docs/icd/servo_gyro.md): reads β = drive_angle_rad [rad], β' =
// drive_rate_rad_s [rad/s], α' = alpha_rate_rad_s [rad/s] (feed-forward); gives M2 = motor_torque_Nm [N m].
// Sampled: k_p T / B ≤ 0.5 (sampled_loop_limits.hpp); defaults at 1 ms: 0.2.
// State: the PI's integral I [N m] (PiState). O(1), no heap. Tests: tests/unit/control_laws_test.cpp (sign,
// rate tracking on B β'' = M2 + H cosβ α', saturation and anti-windup, the torque-to-rate map).
// Docs: docs/models/servo-gyro.md#firmware-law
#pragma once

#include <cmath>

#include "firmware/control/config_check.hpp"
#include "firmware/control/drive_loops.hpp"
#include "firmware/control/sampled_loop_limits.hpp"
#include "firmware/math/deterministic_math.hpp"

namespace gyrostab::firmware {

struct ServoGyroParams {
  // What the law assumes about the plant.
  double B{0.5};  // inner gimbal + rotor about axis 2 [kg m²]
  double H{1.0};  // rotor spin momentum [N m s]
  // Rate loop.
  double rate_kp{100.0};        // k_p [N m s/rad]
  double rate_ki{5000.0};       // k_i [N m/rad]
  bool feedforward{true};       // add (14.43) −H cosβ α'
  double torque_limit_Nm{5.0};  // |M2| ≤ this [N m]
  double cos_beta_floor{0.1};   // gimbal-lock guard of the torque-to-rate map [-], in (0, 1]
};

struct ServoGyroInputs {
  double rate_reference{0.0};  // Ω [rad/s]
  double beta{0.0};            // β [rad]
  double beta_rate{0.0};       // β' [rad/s]
  double alpha_rate{0.0};      // α' [rad/s]
};

struct ServoGyroOutput {
  double torque_Nm{0.0};  // M2 after saturation [N m]
  bool saturated{false};  // clipped (the integral tracks the limit)
  bool valid{true};       // false: a non-finite input; M2 = 0 and the integral unchanged
};

// The rate loop for a fixed control period T [s]: compiled PI coefficients and the integral. O(1) per step.
class ServoGyroRateLoop {
 public:
  ServoGyroRateLoop(const ServoGyroParams& p, double T) : p_(p), pi_(compile_pi(pi_params(p, T))) {}

  static PiParams<double> pi_params(const ServoGyroParams& p, double T) {
    PiParams<double> pi;
    pi.kp = p.rate_kp;
    pi.ki = p.rate_ki;
    pi.period = T;
    pi.out_min = -p.torque_limit_Nm;
    pi.out_max = p.torque_limit_Nm;
    return pi;  // tracking_time 0 = T, back-calculation
  }

  ServoGyroOutput step(const ServoGyroInputs& in) {
    const double ff = p_.feedforward ? -p_.H * math::cos(in.beta) * in.alpha_rate : 0.0;
    const PiOutput<double> o = pi_step(pi_, state_, in.rate_reference, in.beta_rate, ff);
    return {o.value, o.saturated, o.valid};
  }
  void reset() { state_ = {}; }
  double integral_Nm() const { return state_.integral; }

 private:
  ServoGyroParams p_;
  PiCoefficients<double> pi_;
  PiState<double> state_{};
};

struct ServoGyroRate {
  double rate{0.0};     // Ω [rad/s]
  bool limited{false};  // |cosβ| was below the floor
};

// Ω that makes the gyroscopic reaction on axis 1 equal M1_demand: Ω = −M1_demand / (H cosβ) (14.42), with
// |cosβ| floored at cos_beta_floor (keeping its sign). O(1).
inline ServoGyroRate servo_gyro_rate_for_torque(const ServoGyroParams& p, double M1_demand, double beta) {
  const double cb = math::cos(beta);
  const double mag = cb < 0.0 ? -cb : cb;
  ServoGyroRate r;
  r.limited = mag < p.cos_beta_floor;
  const double cb_used = r.limited ? (cb < 0.0 ? -p.cos_beta_floor : p.cos_beta_floor) : cb;
  r.rate = -M1_demand / (p.H * cb_used);
  return r;
}

// Start-up check for control period T [s]. O(1).
inline ConfigCheck check_servo_gyro(const ServoGyroParams& p, double T) {
  auto finite = [](double x) { return std::isfinite(x); };
  if (!(finite(p.B) && p.B > 0.0 && finite(p.H) && p.H > 0.0)) {
    return ConfigCheck::refused("servo gyro: B and H must be finite and > 0");
  }
  if (!(finite(p.rate_kp) && p.rate_kp > 0.0 && finite(p.rate_ki) && p.rate_ki >= 0.0)) {
    return ConfigCheck::refused("servo gyro: rate_kp must be > 0 and rate_ki >= 0 (finite)", p.rate_kp);
  }
  if (!(finite(p.torque_limit_Nm) && p.torque_limit_Nm > 0.0)) {
    return ConfigCheck::refused("servo gyro: torque_limit_Nm must be finite and > 0", p.torque_limit_Nm);
  }
  if (!(p.cos_beta_floor > 0.0 && p.cos_beta_floor <= 1.0)) {
    return ConfigCheck::refused("servo gyro: cos_beta_floor must lie in (0, 1]", p.cos_beta_floor, 0.0, 1.0);
  }
  if (const char* why = check_pi(ServoGyroRateLoop::pi_params(p, T))) return ConfigCheck::refused(why);
  const double kp_max = max_sampled_damping(p.B, T);
  if (!(p.rate_kp <= kp_max)) {
    return ConfigCheck::refused("servo gyro: rate_kp T / B > 0.5, the sampled rate loop oscillates",
                                p.rate_kp, 0.0, kp_max);
  }
  return ConfigCheck::accepted();
}

}  // namespace gyrostab::firmware
