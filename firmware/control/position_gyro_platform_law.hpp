// The amplifier and the slew command of a single-axis platform held by a position (2-DOF) gyro (Magnus
// §16.2.2, (16.6)-(16.10), docs/models/position-gyro-platform.md): the gyro's outer gimbal axis is the
// platform axis; its pick-off measures the platform against the outer gimbal, δ − α, and the amplifier
// drives the platform's torquer
//   M1^KP = −k (δ − α)                           (clipped at ±torque_limit_Nm)
// while the gyro's torquer on its inner axis 2 slews the platform: the gyro frame turns at α0' = −M2^K/H
// (16.7), and the platform follows it with the steady lag (δ − α)0 = M1^SP/k. A commanded slew rate ω_cmd
// gives M2^K = −H ω_cmd between the start and stop ticks (clipped at ±gyro_torque_limit_Nm).
// Sampled: the pick-off read once per control period, the torque held over it (zero-order), acting
// latency_ticks base ticks after the frame it came from.
// Check (start-up): d1, d2 > 0 (undamped: at best marginal); the continuous loop stable by Hurwitz — a gain
// inside Hübner's band k− < k < k+ (position_gyro_platform_stability.hpp) is refused with the band's edges;
// the sampled loop's discrete closed-loop spectral radius ρ < 1 at the control period and the latency.
// Signals: reads δ − α (the pick-off, pickoff_rad) [rad]; gives M1^KP (platform torquer, platform_torquer_Nm)
// and M2^K (gyro torquer, gyro_torquer_Nm) [N m] (the position-gyro platform's signal table,
// docs/icd/position_gyro_platform.md).
// State: none besides the parameters (the schedule reads the frame's tick). O(1) per step, no heap.
// Tests: tests/oracle/position_gyro_platform_test.cpp. Docs: docs/models/position-gyro-platform.md#firmware-law
#pragma once

#include <cmath>
#include <cstdint>

#include "firmware/control/config_check.hpp"
#include "firmware/control/position_gyro_platform_stability.hpp"
#include "firmware/control/saturation.hpp"

namespace gyrostab::firmware {

struct PositionGyroPlatformParams {
  PositionGyroPlatformPlant plant{};  // what the law and its check assume about the plant
  double k{1200.0};                   // amplifier gain M1^KP = −k(δ − α) [N m/rad]
  double torque_limit_Nm{5.0};        // platform torquer limit [N m]
  double gyro_torque_limit_Nm{0.5};   // gyro torquer limit [N m]
  double slew_rate_rad_s{0.0};        // commanded platform rate ω_cmd while slewing [rad/s]
  std::uint64_t slew_start_tick{0};   // first tick of the slew
  std::uint64_t slew_stop_tick{0};    // first tick after it
  std::uint32_t latency_ticks{1};     // base ticks from a frame to its command's action (for the check)
  std::uint32_t pad_{0};
};

struct PositionGyroPlatformCommand {
  double platform_torque_Nm{0.0};  // M1^KP
  double gyro_torque_Nm{0.0};      // M2^K
  bool limited{false};             // a torquer was clipped
};

// The command for the frame of `tick` with pick-off e = δ − α [rad]. O(1).
inline PositionGyroPlatformCommand position_gyro_platform_step(const PositionGyroPlatformParams& p,
                                                                std::uint64_t tick, double pickoff) {
  PositionGyroPlatformCommand c;
  const double m1 = -p.k * pickoff;
  const bool slewing = tick >= p.slew_start_tick && tick < p.slew_stop_tick;
  const double m2 = slewing ? -p.plant.H * p.slew_rate_rad_s : 0.0;
  const Clipped c1 = clip_symmetric(m1, p.torque_limit_Nm);
  const Clipped c2 = clip_symmetric(m2, p.gyro_torque_limit_Nm);
  c.platform_torque_Nm = c1.value;
  c.gyro_torque_Nm = c2.value;
  c.limited = c1.clipped || c2.clipped;
  return c;
}

// Start-up check at control period Tc and base tick T [s]. Not O(1) in spirit: the sampled part builds the
// discrete closed loop (a few small matrix products), once.
inline ConfigCheck check_position_gyro_platform(const PositionGyroPlatformParams& p, double Tc, double T) {
  const auto fin = [](double v) { return std::isfinite(v); };
  const PositionGyroPlatformPlant& s = p.plant;
  if (!(fin(s.Theta) && s.Theta > 0.0 && fin(s.A) && s.A > 0.0 && fin(s.B) && s.B > 0.0 && fin(s.H) &&
        s.H > 0.0)) {
    return ConfigCheck::refused("position gyro platform: Theta, A, B, H must be finite and > 0");
  }
  if (!(fin(s.d1) && fin(s.d2) && s.d1 >= 0.0 && s.d2 >= 0.0)) {
    return ConfigCheck::refused("position gyro platform: d1, d2 must be finite and >= 0");
  }
  if (s.d1 == 0.0 && s.d2 == 0.0) {
    return ConfigCheck::refused(
        "position gyro platform: undamped (d1 = d2 = 0): the lambda and lambda^3 terms of (16.8) vanish, at best "
        "marginally stable");
  }
  if (!(fin(p.k) && p.k > 0.0)) {
    return ConfigCheck::refused("position gyro platform: amplifier gain k must be finite and > 0", p.k);
  }
  if (!(fin(p.torque_limit_Nm) && p.torque_limit_Nm > 0.0 && fin(p.gyro_torque_limit_Nm) &&
        p.gyro_torque_limit_Nm > 0.0)) {
    return ConfigCheck::refused("position gyro platform: torque limits must be finite and > 0");
  }
  if (!fin(p.slew_rate_rad_s)) return ConfigCheck::refused("position gyro platform: slew rate must be finite");
  if (!(p.latency_ticks <= 16u)) {
    return ConfigCheck::refused("position gyro platform: latency_ticks must be <= 16",
                                static_cast<double>(p.latency_ticks), 0.0, 16.0);
  }
  const HurwitzResult h = platform_hurwitz(s, p.k);
  if (!h.stable) {
    const PlatformGainBand b = platform_gain_band(s);
    if (b.exists && p.k > b.lower && p.k < b.upper) {
      return ConfigCheck::refused(
          "position gyro platform: gain k inside the unstable band of (16.9), D^III(k) < 0 between its roots "
          "k- and k+",
          p.k, b.lower, b.upper);
    }
    if (!h.coefficients_positive) {
      return ConfigCheck::refused("position gyro platform: a coefficient of (16.8) is not positive (unstable)",
                                  p.k);
    }
    return ConfigCheck::refused("position gyro platform: the Hurwitz determinants of (16.9) are not positive",
                                p.k);
  }
  if (!(fin(Tc) && Tc > 0.0 && fin(T) && T > 0.0)) {
    return ConfigCheck::refused("position gyro platform: control period must be > 0");
  }
  const double tau = static_cast<double>(p.latency_ticks) * T;
  if (!(tau <= 16.0 * Tc)) {
    return ConfigCheck::refused("position gyro platform: latency beyond 16 control periods", tau, 0.0, 16.0 * Tc);
  }
  const double rho = platform_sampled_radius(s, p.k, Tc, tau);
  if (!(rho < 1.0)) {
    return ConfigCheck::refused(
        "position gyro platform: the sampled loop (zero-order hold, control period, latency) is unstable: "
        "spectral radius of the discrete closed loop >= 1 (value rho)",
        rho, 0.0, 1.0);
  }
  return ConfigCheck::accepted();
}

}  // namespace gyrostab::firmware
