// The coning platform's slaving loop (Magnus §15.5, docs/models/coning.md): a geared servo turns the platform
// about its axis 3 so that the single-axis gyro on it (input axis = platform axis 3) reads zero.
//
// Indicated angle θ of the platform about axis 3 from the gyro's output angle β:
//   P-gyro:  θ ← θ + (c2/H) β T     (the reading (c2/H) β is a rate, (15.4); integrated here)
//   I-gyro:  θ = (d2/H) β           (the reading is the angle itself, (15.16))
// Rate command to the drive (PI on θ, through the drive's K_v): u = −k_p θ − k_i ∫θ dt, V = u / K_v, clipped
// at ±voltage_limit with the back-calculation anti-windup of drive_loops.hpp (pi_step).
// With an ideal gyro and drive (θ' = ω_p3 + ω̄_err, φ' = u) the loop is s² + k_p s + k_i: defaults k_p = 1/s,
// k_i = 0.25/s² give a double pole at 0.5 rad/s — far below the vibration (ν ≈ 30 rad/s), so the platform
// follows the base's vibration (the gyro sees it and rectifies it) while the mean reading is nulled; the
// loop's sensitivity at ν, 1 + O(k_p/ν), changes the rectified rate by O(k_p/ν)² (coning_closed_forms.hpp).
// Drive lag τ_d: τ_d s³ + s² + k_p s + k_i is stable iff k_i τ_d < k_p (Routh).
// Signals (through firmware/app/coning_controller.hpp): β [rad] is the coning sensor frame's beta_rad, V [V]
// its actuator frame's drive_voltage_V.
// check(): finite, k_p > 0, k_i ≥ 0, scale > 0, K_v > 0, τ_d ≥ 0, voltage limit > 0; k_i τ_d ≤ k_p/2 (Routh with
// a factor 2 of margin); k_p T ≤ 0.5 and k_p τ_d ≤ 0.5 (the sampling and the drive lag well outside the loop's
// crossover ≈ k_p, as sampled_loop_limits.hpp asks of a rate loop).
// State: θ [rad] (P-gyro), the PI's integral [V]. O(1), no heap.
// Tests: tests/oracle/coning_test.cpp (the closed loop). Docs: docs/models/coning.md#firmware-law
#pragma once

#include <cmath>

#include "firmware/control/config_check.hpp"
#include "firmware/control/drive_loops.hpp"

namespace gyrostab::firmware {

struct ConingNullParams {
  bool integrating{false};          // false: P-gyro (rate reading); true: I-gyro (angle reading)
  double scale{8.0};                // c2/H [1/s] (P) or d2/H [-] (I): β → the reading
  double kp{1.0};                   // k_p [1/s]
  double ki{0.25};                  // k_i [1/s²]
  double rate_per_volt{0.1};        // K_v of the drive [rad/s per V]
  double drive_time_constant{0.005};  // τ_d the law assumes [s]
  double voltage_limit{10.0};       // |V| ≤ this [V]
};

struct ConingNullOutput {
  double voltage{0.0};    // V after the clip [V]
  bool saturated{false};  // clipped
  bool valid{true};       // false: a non-finite input; V = 0, state unchanged
};

class ConingNullLoop {
 public:
  ConingNullLoop(const ConingNullParams& p, double T) : p_(p), T_(T), pi_(compile_pi(pi_params(p, T))) {}

  static PiParams<double> pi_params(const ConingNullParams& p, double T) {
    PiParams<double> pi;
    pi.kp = p.kp / p.rate_per_volt;
    pi.ki = p.ki / p.rate_per_volt;
    pi.period = T;
    pi.out_min = -p.voltage_limit;
    pi.out_max = p.voltage_limit;
    return pi;
  }

  ConingNullOutput step(double beta) {
    if (!std::isfinite(beta)) return {0.0, false, false};
    if (p_.integrating) {
      theta_ = p_.scale * beta;
    } else {
      theta_ += p_.scale * beta * T_;
    }
    const PiOutput<double> o = pi_step(pi_, state_, 0.0, theta_);
    return {o.value, o.saturated, o.valid};
  }
  void reset() {
    state_ = {};
    theta_ = 0.0;
  }
  double indicated_angle() const { return theta_; }  // θ [rad]

 private:
  ConingNullParams p_;
  double T_;
  PiCoefficients<double> pi_;
  PiState<double> state_{};
  double theta_{0.0};
};

// Start-up check for control period T [s]. O(1).
inline ConfigCheck check_coning_null(const ConingNullParams& p, double T) {
  const auto finite = [](double x) { return std::isfinite(x); };
  if (!(finite(p.scale) && p.scale > 0.0)) return ConfigCheck::refused("coning: scale must be finite and > 0", p.scale);
  if (!(finite(p.kp) && p.kp > 0.0 && finite(p.ki) && p.ki >= 0.0)) {
    return ConfigCheck::refused("coning: kp must be > 0 and ki >= 0 (finite)", p.kp);
  }
  if (!(finite(p.rate_per_volt) && p.rate_per_volt > 0.0)) {
    return ConfigCheck::refused("coning: rate_per_volt must be finite and > 0", p.rate_per_volt);
  }
  if (!(finite(p.drive_time_constant) && p.drive_time_constant >= 0.0)) {
    return ConfigCheck::refused("coning: drive_time_constant must be finite and >= 0", p.drive_time_constant);
  }
  if (!(finite(p.voltage_limit) && p.voltage_limit > 0.0)) {
    return ConfigCheck::refused("coning: voltage_limit must be finite and > 0", p.voltage_limit);
  }
  if (const char* why = check_pi(ConingNullLoop::pi_params(p, T))) return ConfigCheck::refused(why);
  if (!(p.ki * p.drive_time_constant <= 0.5 * p.kp)) {
    return ConfigCheck::refused("coning: ki tau_d > kp/2, the loop with the drive lag is near instability (Routh)",
                                p.ki, 0.0, 0.5 * p.kp / p.drive_time_constant);
  }
  const double kp_max = 0.5 / (T > p.drive_time_constant ? T : p.drive_time_constant);
  if (!(p.kp <= kp_max)) {
    return ConfigCheck::refused("coning: kp max(T, tau_d) > 0.5, the sampling or the drive lag reaches the crossover",
                                p.kp, 0.0, kp_max);
  }
  return ConfigCheck::accepted();
}

}  // namespace gyrostab::firmware
