// Torque → current → voltage: the inner drive loop of one gimbal axis, for drives that take a terminal
// voltage (ActuatorFrame::motor_voltage_V) instead of a torque. The control law's torque command M becomes
// a current reference i_ref = M / k_t (clipped to ±current_limit_A), and the current PI of
// firmware/control/drive_loops.hpp (design_current_pi: exact discrete pole placement on the ZOH winding
// L di/dt = u − R i − k_e ω, back-calculation anti-windup) turns it into the voltage, with the back-EMF fed
// forward, u_ff = k_e β' (or α' on axis 1):
//   u = clamp(K_p (i_ref − i) + I + k_e ω, ±voltage_limit_V)
// Runs as the runtime's drive task at the drive period T_d (firmware/app/controller_runtime.hpp), which may
// be shorter than the control period (e.g. 10 kHz vs 1 kHz); the torque command is held between control
// runs. With the one tick of latency of the contract the closed current loop keeps real poles only while
// ω_c T_d ≤ ln(4/3) ≈ 0.29 (drive_loops.hpp), which the check enforces.
// Signals: reads SensorFrame motor_current_A[axis] = i [A], gimbal_rate_rad_s[axis] = ω [rad/s] (at the
// gimbal; k_e and k_t are referred to the gimbal shaft, i.e. include the gear ratio). Writes ActuatorFrame
// motor_voltage_V[axis] [V]. The torque field is left as the law wrote it (a torque-mode plant reads that).
// State: one PI integral [V]. O(1), no heap. Tests: through tests/unit/controllers_test.cpp.
// Docs: docs/models/drives.md#firmware-drive-loops
#pragma once

#include <cmath>

#include "firmware/control/config_check.hpp"
#include "firmware/control/drive_loops.hpp"
#include "firmware/control/saturation.hpp"
#include "firmware/math/deterministic_math.hpp"

namespace gyrostab::firmware {

struct TorqueCurrentLoopParams {
  double torque_constant_Nm_per_A{1.0};  // k_t at the gimbal (geared: N η k_t) [N m/A]
  double back_emf_V_s_per_rad{0.0};      // k_e at the gimbal [V s/rad]; 0: no feed-forward
  double resistance_ohm{1.0};            // winding R [Ω]
  double inductance_H{1e-3};             // winding L [H]
  double bandwidth_rad_s{2000.0};        // ω_c of the closed current loop [rad/s]
  double current_limit_A{10.0};          // |i_ref| ≤ this [A]
  double voltage_limit_V{24.0};          // |u| ≤ this [V]
};

struct TorqueCurrentOutput {
  double voltage_V{0.0};  // u [V]
  bool saturated{false};  // the voltage or the current reference was clipped
  bool valid{true};       // false: non-finite input; u = 0, integral unchanged
};

inline PiParams<double> torque_current_pi_params(const TorqueCurrentLoopParams& p, double T) {
  CurrentLoopSpec spec;
  spec.resistance = p.resistance_ohm;
  spec.inductance = p.inductance_H;
  spec.bandwidth = p.bandwidth_rad_s;
  spec.period = T;
  spec.voltage_limit = p.voltage_limit_V;
  return design_current_pi(spec);
}

class TorqueCurrentLoop {
 public:
  TorqueCurrentLoop() = default;
  TorqueCurrentLoop(const TorqueCurrentLoopParams& p, double T)
      : p_(p), pi_(compile_pi(torque_current_pi_params(p, T))) {}

  // One drive tick: torque command [N m], measured current [A], gimbal rate [rad/s]. O(1).
  TorqueCurrentOutput step(double torque_Nm, double current_A, double gimbal_rate) {
    const Clipped i_ref = clip_symmetric(torque_Nm / p_.torque_constant_Nm_per_A, p_.current_limit_A);
    const PiOutput<double> o =
        pi_step(pi_, state_, i_ref.value, current_A, p_.back_emf_V_s_per_rad * gimbal_rate);
    return {o.value, o.saturated || i_ref.clipped, o.valid};
  }
  void reset() { state_ = {}; }

 private:
  TorqueCurrentLoopParams p_{};
  PiCoefficients<double> pi_{};
  PiState<double> state_{};
};

// Start-up check at drive period T [s]. O(1).
inline ConfigCheck check_torque_current_loop(const TorqueCurrentLoopParams& p, double T) {
  auto pos = [](double x) { return std::isfinite(x) && x > 0.0; };
  if (!pos(p.torque_constant_Nm_per_A)) return ConfigCheck::refused("drive: torque_constant must be > 0");
  if (!(std::isfinite(p.back_emf_V_s_per_rad) && p.back_emf_V_s_per_rad >= 0.0)) {
    return ConfigCheck::refused("drive: back_emf constant must be finite and >= 0");
  }
  if (!pos(p.resistance_ohm) || !(std::isfinite(p.inductance_H) && p.inductance_H >= 0.0)) {
    return ConfigCheck::refused("drive: resistance must be > 0 and inductance >= 0");
  }
  if (!pos(p.current_limit_A) || !pos(p.voltage_limit_V)) {
    return ConfigCheck::refused("drive: current_limit and voltage_limit must be > 0");
  }
  const double bw_max = math::log(4.0 / 3.0) / T;
  if (!pos(p.bandwidth_rad_s) || !(p.bandwidth_rad_s <= bw_max)) {
    return ConfigCheck::refused(
        "drive: current-loop bandwidth must lie in (0, ln(4/3)/T_drive] (real poles with "
        "one tick of latency, drive_loops.hpp)",
        p.bandwidth_rad_s, 0.0, bw_max);
  }
  if (const char* why = check_pi(torque_current_pi_params(p, T))) return ConfigCheck::refused(why);
  return ConfigCheck::accepted();
}

}  // namespace gyrostab::firmware
