// Monorail motor law with damper (Magnus §14.1, docs/models/monorail.md): the motor on the gyro-case
// axis 2 is commanded from the car's tilt, and the damper is realised by the same motor:
//   M2 = k φ − d β'                                          (the right-hand side of (14.2))  [N m]
// so that the car + case obey (14.2)   A φ'' − c φ + H β' = 0,   B β'' + d β' − q β − H φ' − k φ = 0.
// Start-up check: the gains must lie in the window where (14.3)
//   AB λ⁴ + A d λ³ + (H² − qA − cB) λ² + (kH − cd) λ + cq = 0
// is Hurwitz ((14.5): kH − cd > 0, D^II > 0, D^III > 0). For c, q > 0 and H > sqrt(qA) + sqrt(cB) (the gyro
// is strong enough, (14.4)) this is the gain window [derived, docs/models/monorail.md]
//   d (c + A ω_P²) / H  <  k  <  d (c + A ω_N²) / H,
//   ω_P² < ω_N² the roots of  AB Ω⁴ − (H² − qA − cB) Ω² + cq = 0.
// The law refuses k outside it and reports both bounds; the Hurwitz determinants of (14.5) are evaluated
// too (firmware/control/hurwitz.hpp) and must agree. d in the check is the total damping on axis 2: the
// commanded d plus d_mechanical, a passive damper the plant may have (then set the commanded d lower).
// The constructed reference car (defaults): A 3000, c 2e4, B 50, q 500, H 4000, d 200 → ω_P = 0.864,
// ω_N = 9.447 rad/s, window 1112 < k < 14388 N m/rad; k = 7750 (default) gives max Re λ = −0.486 1/s.
// Signals: reads φ (car tilt, tilt_rad) [rad] and β' (case_rate_rad_s) [rad/s]; gives M2 (motor_torque_Nm)
// [N m], clipped to ±torque_limit_Nm (the monorail's signal table, docs/icd/monorail.md). The plant's
// own analog motor law (sim/models/monorail.hpp, MonorailParams::k) must be 0 when this law drives M2.
// Sampled: d T / B ≤ 0.5 (sampled_loop_limits.hpp); defaults at 1 ms: 0.004.
// State: none. O(1), no heap. Tests: tests/unit/control_laws_test.cpp (sign, saturation, window refusal on
// both sides against the reference car's numbers).
// Docs: docs/models/monorail.md#firmware-law
#pragma once

#include <cmath>

#include "firmware/control/config_check.hpp"
#include "firmware/control/hurwitz.hpp"
#include "firmware/control/sampled_loop_limits.hpp"
#include "firmware/control/saturation.hpp"

namespace gyrostab::firmware {

struct MonorailMotorParams {
  // What the law assumes about the plant (used by the gain check only).
  double A{3000.0};          // car inertia about the rail [kg m²]
  double B{50.0};            // case + rotor about axis 2 [kg m²]
  double c{2.0e4};           // overturning stiffness of the car m g h [N m/rad]
  double q{500.0};           // overturning stiffness of the case G s [N m/rad]
  double H{4000.0};          // rotor spin momentum [N m s]
  double d_mechanical{0.0};  // passive damper of the plant on axis 2 (adds to d in the check) [N m s/rad]
  // The law.
  double k{7750.0};                // motor gain on the car tilt [N m/rad]
  double d{200.0};                 // damper realised by the motor [N m s/rad]
  double torque_limit_Nm{2000.0};  // |M2| ≤ this [N m]
};

// (14.2): M2 = k φ − d β', clipped. Pure function.
constexpr Clipped monorail_motor_torque(const MonorailMotorParams& p, double phi, double beta_rate) {
  return clip_symmetric(p.k * phi - p.d * beta_rate, p.torque_limit_Nm);
}

struct MonorailGainWindow {
  bool gyro_strong_enough{false};  // c > 0, q > 0 and H > sqrt(qA) + sqrt(cB) (14.4)
  double H_min{0.0};               // sqrt(qA) + sqrt(cB) [N m s]
  double omega_P{0.0};             // precession frequency of the undamped loop [rad/s]
  double omega_N{0.0};             // nutation frequency of the undamped loop [rad/s]
  double k_min{0.0};               // d_total (c + A ω_P²) / H [N m/rad]
  double k_max{0.0};               // d_total (c + A ω_N²) / H [N m/rad]
  HurwitzResult hurwitz{};         // (14.5) for the configured k and d_total
};

// The window for the configured plant and d_total = d + d_mechanical, and the Hurwitz test of (14.3) at the
// configured k. O(1).
inline MonorailGainWindow monorail_gain_window(const MonorailMotorParams& p) {
  MonorailGainWindow w;
  const double d = p.d + p.d_mechanical;
  const double S = p.H * p.H - p.q * p.A - p.c * p.B;  // λ² coefficient of (14.3)
  w.hurwitz = hurwitz_quartic(p.A * p.B, p.A * d, S, p.k * p.H - p.c * d, p.c * p.q);
  if (!(p.c > 0.0 && p.q > 0.0 && p.A > 0.0 && p.B > 0.0 && p.H > 0.0)) return w;
  w.H_min = std::sqrt(p.q * p.A) + std::sqrt(p.c * p.B);
  const double disc = S * S - 4.0 * p.A * p.B * p.c * p.q;
  w.gyro_strong_enough = p.H > w.H_min && S > 0.0 && disc > 0.0;
  if (!w.gyro_strong_enough) return w;
  const double root = std::sqrt(disc);
  // Ω² = (S ∓ root) / (2AB); the smaller one as cq / (AB Ω_N²) to avoid cancellation.
  const double wN2 = (S + root) / (2.0 * p.A * p.B);
  const double wP2 = p.c * p.q / (p.A * p.B * wN2);
  w.omega_N = std::sqrt(wN2);
  w.omega_P = std::sqrt(wP2);
  w.k_min = d * (p.c + p.A * wP2) / p.H;
  w.k_max = d * (p.c + p.A * wN2) / p.H;
  return w;
}

// Start-up check for control period T [s]: plant positive, gyro strong enough (14.4), k inside the window
// (refused with value = k, lower = k_min, upper = k_max), Hurwitz (14.5) agreeing, limit > 0, d sampled
// bound. O(1).
inline ConfigCheck check_monorail_motor(const MonorailMotorParams& p, double T) {
  auto finite = [](double x) { return std::isfinite(x); };
  if (!(finite(p.A) && finite(p.B) && finite(p.c) && finite(p.q) && finite(p.H) && p.A > 0.0 && p.B > 0.0 &&
        p.H > 0.0)) {
    return ConfigCheck::refused("monorail: A, B, H must be finite and > 0, c, q finite");
  }
  if (!(p.c > 0.0 && p.q > 0.0)) {
    return ConfigCheck::refused(
        "monorail: c > 0 and q > 0 needed: the coefficient c q of (14.3) must be > 0 (car and case both "
        "statically unstable, (14.4) 2))");
  }
  if (!(finite(p.d) && p.d >= 0.0 && finite(p.d_mechanical) && p.d_mechanical >= 0.0 && finite(p.k))) {
    return ConfigCheck::refused("monorail: k must be finite, d and d_mechanical finite and >= 0");
  }
  if (!(finite(p.torque_limit_Nm) && p.torque_limit_Nm > 0.0)) {
    return ConfigCheck::refused("monorail: torque_limit_Nm must be finite and > 0", p.torque_limit_Nm);
  }
  const MonorailGainWindow w = monorail_gain_window(p);
  if (!w.gyro_strong_enough) {
    return ConfigCheck::refused(
        "monorail: gyro too weak, H must exceed sqrt(qA) + sqrt(cB) (14.4) for any gain window to exist", p.H,
        w.H_min, 0.0);
  }
  if (!(p.d + p.d_mechanical > 0.0)) {
    return ConfigCheck::refused(
        "monorail: d + d_mechanical = 0 makes the lambda^3 coefficient A d of (14.3) zero:"
        " unstable for every k (14.5)",
        p.k, w.k_min, w.k_max);
  }
  if (!(p.k > w.k_min)) {
    return ConfigCheck::refused(
        "monorail: k <= d (c + A w_P^2) / H, below the gain window of (14.5): the "
        "precession mode grows",
        p.k, w.k_min, w.k_max);
  }
  if (!(p.k < w.k_max)) {
    return ConfigCheck::refused(
        "monorail: k >= d (c + A w_N^2) / H, above the gain window of (14.5): the "
        "nutation mode grows",
        p.k, w.k_min, w.k_max);
  }
  if (!w.hurwitz.stable) {
    return ConfigCheck::refused(
        "monorail: inside the window but the Hurwitz determinants of (14.5) are not "
        "positive (k at the window's edge to rounding)",
        p.k, w.k_min, w.k_max);
  }
  const double d_max = max_sampled_damping(p.B, T);
  if (!(p.d <= d_max)) {
    return ConfigCheck::refused("monorail: d T / B > 0.5, the sampled damper oscillates", p.d, 0.0, d_max);
  }
  return ConfigCheck::accepted();
}

}  // namespace gyrostab::firmware
