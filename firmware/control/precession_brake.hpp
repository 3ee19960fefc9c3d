// Passive precession brake of the ship roll damper: the viscous brake d2 of Magnus §14.2 realised by the
// precession drive, commanded as a torque on the case axis 2.
//
// Book (Magnus §14.2):                 (14.8)  A φ'' + d1 φ' + c φ + H β' = E(t),
//                                             B β'' + d2 β' + q β − H φ' = M2.
// The term d2 β' of (14.8) moved to the right-hand side is the torque the brake applies to the case:
//   M2 = −d2 β'                                  → the command precession_torque_Nm  [N m]
// clipped to ±torque_limit_Nm; the command precession_brake stays 0 (released). Why the torque field and
// not the brake fraction: the contract defines precession_brake = 1 as "case locked to the carrier" (the
// safe state's holding brake), and a fraction would need a plant-side map from fraction to N m s/rad that
// the contract does not define; a torque −d2 β' is exactly the (14.8) term whatever the actuator is. So the
// plant's own d2 must be 0 when this law is in the loop (else the damping is counted twice).
// d2 is a parameter: Hahnkamm's minimax value (the d2 whose maximum of φ_A(ω) passes through the higher
// invariant point ω_II or ω_III of (14.17)-(14.18)) is computed off-line; for the constructed reference ship
// (A 3.2e7, c 1.1772e7, B 1.5e4, q 1350, H 1.018e6) it is ≈ 4.53e4 N m s/rad (the default), peak roll
// 1.06 × static.
// Signals: reads β' (precession_rate_rad_s) [rad/s]; gives M2 (precession_torque_Nm) [N m] (the ship roll
// damper's signal table, docs/icd/ship_roll_damper.md).
// Sampled: D = d2 must satisfy d2 T / B ≤ 0.5 (sampled_loop_limits.hpp); for the defaults at 1 ms 0.003.
// State: none. O(1), no heap. Tests: tests/unit/control_laws_test.cpp (sign, saturation, check).
// Docs: docs/models/ship-roll-damper.md#firmware-laws
#pragma once

#include <cmath>

#include "firmware/control/config_check.hpp"
#include "firmware/control/sampled_loop_limits.hpp"
#include "firmware/control/saturation.hpp"

namespace gyrostab::firmware {

struct PrecessionBrakeParams {
  double d2{4.53e4};              // viscous brake coefficient (minimax of (14.18), default ship) [N m s/rad]
  double torque_limit_Nm{2.0e5};  // largest brake torque the precession drive delivers [N m]
  double B{1.5e4};                // case + rotor inertia about axis 2, for the sampled-loop check [kg m²]
};

// The brake torque on axis 2 and whether it saturated. Pure function.
constexpr Clipped precession_brake_torque(const PrecessionBrakeParams& p, double beta_rate) {
  return clip_symmetric(-p.d2 * beta_rate, p.torque_limit_Nm);
}

// d2 ≥ 0 and finite, limit > 0, and the sampled-loop bound d2 ≤ 0.5 B / T at control period T [s]. O(1).
inline ConfigCheck check_precession_brake(const PrecessionBrakeParams& p, double T) {
  if (!(std::isfinite(p.B) && p.B > 0.0)) return ConfigCheck::refused("brake: B must be finite and > 0", p.B);
  if (!(std::isfinite(p.d2) && p.d2 >= 0.0))
    return ConfigCheck::refused("brake: d2 must be finite and >= 0", p.d2);
  if (!(std::isfinite(p.torque_limit_Nm) && p.torque_limit_Nm > 0.0)) {
    return ConfigCheck::refused("brake: torque_limit_Nm must be finite and > 0", p.torque_limit_Nm);
  }
  const double d_max = max_sampled_damping(p.B, T);
  if (!(p.d2 <= d_max)) {
    return ConfigCheck::refused(
        "brake: d2 T / B > 0.5, the sampled brake oscillates (sampled_loop_limits.hpp)", p.d2, 0.0, d_max);
  }
  return ConfigCheck::accepted();
}

}  // namespace gyrostab::firmware
