// Schuler loop of a levelled inertial platform: each horizontal channel integrates its accelerometer into a
// commanded platform rate (the level frame's rate v/R) and torques the gyro that holds that platform axis,
// so that the platform follows the local level with the undisturbed period 2π sqrt(R/g) = 84.4 min.
//
// Book: Magnus §16.4.2 (docs/models/inertial-platform.md), Fig. 16.9:
//   (16.36)  α' = α'_soll = (1/R) ∫ b^M dt            (16.39)  M2^K = −(H/R) ∫ b^M dt
//   (16.37)  (α − ϑ)'' + (g/R)(α − ϑ) = 0           (16.38)  T = 2π sqrt(R/g) = 84.4 min
//   (16.44)  λ1,2 = ±i sqrt(g/R) — [OCR-fix] printed ±i sqrt(R/g); (16.43) gives sqrt(g/R).
// The loop reads each channel's apparent tilt θ_i = the platform's tilt about its axis i from the apparent
// level as its accelerometer senses it (θ = −b^M/g0 for the book's single axis; the inertial platform's
// theta1_rad, theta2_rad, scale g0 = 9.80665 m/s²; see sim/models/inertial_platform.hpp), averaged over the
// control period by an integrating (Δv) accelerometer, so that the sum below is the exact integral of the
// specific force; on every channel
//   ω_cmd,i ← ω_cmd,i − (g0/R) θ_i T          (forward Euler at the control period T)
//   M_i = −H ω_cmd,i                          (torquer on the channel's gyro, (16.39))
// ω_cmd starts at initial_rate (the level frame's rate after alignment: v0/R, incl. the Earth's rate —
// with ω_cmd(0) ≠ Ω(0) the platform swings at 84.4 min with amplitude |Δω|/ω_S, (16.49)).
// Tuning: R must be the Earth's radius; a different R gives period 2π sqrt(R_loop/g) and a residual error
// under acceleration — the untuned case of (16.31) / (16.48).
// On a withheld frame the runtime calls reset(): the velocity estimate is KEPT (it is navigation state, not
// a control transient; zeroing it would throw the platform off level by v/(R ω_S)); the safe state's zero
// torque lets the platform hold its inertial attitude instead.
// Sampled: the forward-Euler integrator plus one tick of latency lag the loop by ≈ 1.5 T: the Schuler mode
// then grows by ≈ ω_S² · 1.5 T / 2 per second (2e-9/s at T = 1 ms) — negligible against gyro drift; the
// check refuses ω_S T > 1e-2 (a period typed in the wrong unit).
// Signals: reads θ_1, θ_2 [rad]; writes M_1, M_2 [N m] (clipped at ±torque_limit_Nm). O(1), no heap.
// Tests: tests/unit/gyro_instrument_laws_test.cpp; closed loop tests/oracle/inertial_platform_test.cpp.
// Docs: docs/models/inertial-platform.md#firmware-law
#pragma once

#include <cmath>
#include <cstddef>

#include "firmware/control/config_check.hpp"

namespace gyrostab::firmware {

inline constexpr std::size_t kSchulerChannels = 2;

struct SchulerLoopParams {
  double radius{6.371e6};         // R the loop is tuned to [m]
  double gravity_scale{9.80665};  // g0: θ = b / g0 in the sensor frame [m/s²]
  double H{0.1};                  // spin momentum of the channel gyros (torquer scale) [N m s]
  double initial_rate[kSchulerChannels]{0.0, 0.0};  // ω_cmd at start [rad/s]
  bool enabled[kSchulerChannels]{true, true};      // a disabled channel commands zero torque
  double torque_limit_Nm{1.0};    // |M_i| ≤ this [N m]
};

struct SchulerTorques {
  double M[kSchulerChannels]{0.0, 0.0};  // [N m]
  bool limited{false};
};

class SchulerLoop {
 public:
  SchulerLoop(const SchulerLoopParams& p, double T) : p_(p), gain_(p.gravity_scale / p.radius * T) {
    for (std::size_t i = 0; i < kSchulerChannels; ++i) rate_[i] = p_.initial_rate[i];
  }

  // One control period with the apparent tilts θ [rad]; integrate = false (a held frame) or a non-finite θ
  // leaves the estimate unchanged and only re-issues the torque.
  SchulerTorques step(const double (&theta)[kSchulerChannels], bool integrate = true) {
    SchulerTorques out;
    for (std::size_t i = 0; i < kSchulerChannels; ++i) {
      if (!p_.enabled[i]) continue;
      if (integrate && std::isfinite(theta[i])) rate_[i] -= gain_ * theta[i];
      double M = -p_.H * rate_[i];
      if (M > p_.torque_limit_Nm || M < -p_.torque_limit_Nm) {
        out.limited = true;
        M = M > 0.0 ? p_.torque_limit_Nm : -p_.torque_limit_Nm;
      }
      out.M[i] = M;
    }
    return out;
  }
  void reset() {}  // keeps the estimate (header)

  double commanded_rate(std::size_t i) const { return rate_[i]; }        // ω_cmd,i [rad/s]
  double velocity_estimate(std::size_t i) const { return rate_[i] * p_.radius; }  // R ω_cmd,i [m/s]

 private:
  SchulerLoopParams p_;
  double gain_;  // g0 T / R [1/s]
  double rate_[kSchulerChannels]{0.0, 0.0};
};

// Start-up check for control period T [s]. O(1).
inline ConfigCheck check_schuler_loop(const SchulerLoopParams& p, double T) {
  if (!(std::isfinite(p.radius) && p.radius > 0.0)) {
    return ConfigCheck::refused("schuler loop: radius must be finite and > 0", p.radius);
  }
  if (!(std::isfinite(p.gravity_scale) && p.gravity_scale > 0.0)) {
    return ConfigCheck::refused("schuler loop: gravity_scale must be finite and > 0", p.gravity_scale);
  }
  if (!(std::isfinite(p.H) && p.H > 0.0)) return ConfigCheck::refused("schuler loop: H must be finite and > 0", p.H);
  for (std::size_t i = 0; i < kSchulerChannels; ++i) {
    if (!std::isfinite(p.initial_rate[i]) || std::fabs(p.initial_rate[i]) > 1e-2) {
      return ConfigCheck::refused("schuler loop: initial_rate must be finite with |rate| <= 1e-2 rad/s",
                                  p.initial_rate[i], -1e-2, 1e-2);
    }
  }
  if (!(std::isfinite(p.torque_limit_Nm) && p.torque_limit_Nm > 0.0)) {
    return ConfigCheck::refused("schuler loop: torque_limit_Nm must be finite and > 0", p.torque_limit_Nm);
  }
  if (!(std::isfinite(T) && T > 0.0)) return ConfigCheck::refused("schuler loop: control period must be > 0", T);
  const double wT = std::sqrt(p.gravity_scale / p.radius) * T;
  if (!(wT <= 1e-2)) {
    return ConfigCheck::refused("schuler loop: omega_S T > 1e-2, the control period is far too long for the loop",
                                wT, 0.0, 1e-2);
  }
  return ConfigCheck::accepted();
}

}  // namespace gyrostab::firmware
