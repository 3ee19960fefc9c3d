// Gyrocompass torquer law: damping torque about the vertical and electrical pendulosity about the east axis,
// both from the level sensor on the rotor case (elevation of the rotor axis above the apparent horizon,
// β_lvl = β + b^N/g), plus the tuning formulas the scene and the law use.
//
// Book: Magnus §13.2-13.3 (docs/models/gyrocompass.md):
//   (13.8)   M1 = −f β   (damping / correction torque about the vertical),   M2 = −c β (pendulous torque)
//   (13.9)   δ = f/H,  ω^c = c/H
//   (13.12)  λ = −δ/2 ± i ω^K,  ω^K² = ω^E cosφ (ω^E cosφ + ω^c) − δ²/4
//   (13.26)  Schuler tuning  c/H = g / (R ω^E cosφ)   ⇔   T_K = 2π sqrt(R/g) = 84.4 min (13.27)
// Here M1 = −f β_lvl and M2 = −c_e β_lvl: c_e adds to the sphere's mechanical pendulosity c_m (0 for a
// purely electrical compass), so the total ω^c = (c_m + c_e)/H; a compass tuned by c_e for one latitude is
// mistuned elsewhere — the ballistic deviation then appears (13.28). Damping design: f = 2 ζ ω_n H with
// ω_n² = ω^E cosφ (ω^E cosφ + ω^c) (13.12); it costs the damping error α0 = −δ tanφ/(ω^c + ω^E cosφ) (13.11).
// Signals: reads β_lvl [rad]; writes M1, M2 [N m] clipped to ±torque_limit_Nm. Pure, O(1), no heap.
// Sampled check (period T): f T/H ≤ 0.5 and c_e T/H ≤ 0.5 (precession per radian of tilt per control tick).
// Tests: tests/unit/gyro_instrument_laws_test.cpp; closed loop tests/oracle/gyrocompass_test.cpp.
// Docs: docs/models/gyrocompass.md#firmware-law
#pragma once

#include <cmath>

#include "firmware/control/config_check.hpp"
#include "firmware/math/deterministic_math.hpp"

namespace gyrostab::firmware {

struct GyrocompassLawParams {
  double H{2.0};                // spin momentum the law assumes [N m s]
  double f{0.0};                // damping: M1 = −f β_lvl [N m/rad]
  double c_e{0.0};              // electrical pendulosity: M2 = −c_e β_lvl [N m/rad]
  double torque_limit_Nm{0.1};  // |M1|, |M2| ≤ this [N m]
};

struct GyrocompassTorques {
  double M1{0.0};  // about the vertical [N m]
  double M2{0.0};  // about the east axis [N m]
  bool limited{false};
};

// The law (13.8) on the level sensor. O(1).
inline GyrocompassTorques gyrocompass_torques(const GyrocompassLawParams& p, double beta_level) {
  GyrocompassTorques t{-p.f * beta_level, -p.c_e * beta_level, false};
  const double L = p.torque_limit_Nm;
  if (t.M1 > L || t.M1 < -L || t.M2 > L || t.M2 < -L) t.limited = true;
  t.M1 = t.M1 > L ? L : (t.M1 < -L ? -L : t.M1);
  t.M2 = t.M2 > L ? L : (t.M2 < -L ? -L : t.M2);
  return t;
}

// (13.26): the total pendulous moment c [N m/rad] that Schuler-tunes a compass of momentum H [N m s] at
// latitude φ [rad] (g [m/s²], R [m], ω^E [rad/s]).
inline double schuler_tuned_pendulosity(double H, double latitude, double gravity, double radius,
                                        double earth_rate) {
  return H * gravity / (radius * earth_rate * math::cos(latitude));
}

// Damping f [N m/rad] for damping ratio ζ of (13.12) at latitude φ with total pendulous moment c.
inline double gyrocompass_damping_for_ratio(double H, double c, double latitude, double zeta, double earth_rate) {
  const double wh = earth_rate * math::cos(latitude);
  return 2.0 * zeta * std::sqrt(wh * (wh + c / H)) * H;
}

// Start-up check for control period T [s]. O(1).
inline ConfigCheck check_gyrocompass_law(const GyrocompassLawParams& p, double T) {
  if (!(std::isfinite(p.H) && p.H > 0.0)) return ConfigCheck::refused("gyrocompass: H must be finite and > 0", p.H);
  if (!(std::isfinite(p.f) && p.f >= 0.0 && std::isfinite(p.c_e) && p.c_e >= 0.0)) {
    return ConfigCheck::refused("gyrocompass: f and c_e must be finite and >= 0");
  }
  if (!(std::isfinite(p.torque_limit_Nm) && p.torque_limit_Nm > 0.0)) {
    return ConfigCheck::refused("gyrocompass: torque_limit_Nm must be finite and > 0", p.torque_limit_Nm);
  }
  if (!(std::isfinite(T) && T > 0.0)) return ConfigCheck::refused("gyrocompass: control period must be > 0", T);
  const double max_gain = 0.5 * p.H / T;
  if (!(p.f <= max_gain && p.c_e <= max_gain)) {
    return ConfigCheck::refused("gyrocompass: f T / H or c_e T / H > 0.5, the sampled law oscillates",
                                p.f > p.c_e ? p.f : p.c_e, 0.0, max_gain);
  }
  return ConfigCheck::accepted();
}

}  // namespace gyrostab::firmware
