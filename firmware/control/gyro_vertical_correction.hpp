// Correction laws of the gyro vertical: the torques the torquers on the two gimbal axes apply from the
// erection sensor (rotor-axis tilt from the apparent vertical) and the gimbal rates — the five rows of
// Magnus's table (12.35) (§12.3, docs/models/gyro-vertical.md), each as a pure function, and their sum.
//
// Book, precession equations H β' = M1, −H α' = M2 (12.35), e = (e1, e2) = (α − α_L, β − β_L):
//                               M1                 M2
//   row 1 pendulous             −c1 e1             −c2 e2            (a synthesized pendulum)
//   row 2 viscous               −d1 α'             −d2 β'
//   row 3 Coulomb               −r1 sgn α'         −r2 sgn β'
//   row 4 linear correction     −f1 e2             +f2 e1
//   row 5 relay correction      −g1 sgn e2         +g2 sgn e1
// Rows 4-5 are the non-conservative "correction" proper; rows 1-3 as firmware synthesize what a pendulous
// rotor case or bearing friction would do (the plant has those physically too: sim/models/gyro_vertical.hpp).
// Linear correction alone: H β' = −f1 β, −H α' = f2 α ⇒ α = α0 e^(−f2 t/H), β = β0 e^(−f1 t/H).
// [book slip, corrected] the book prints α ∝ e^(−f1 t/H), β ∝ e^(−f2 t/H); the pairing above is
// the one the printed equations give (identical for f1 = f2, the book's plotted case Fig. 12.11).
// In a level turn the correction follows the apparent vertical and the instrument settles on the turn
// error z_G (12.47) (resonant at ω = −ω^P = −c/H); the book's remedy — switch the correction off during
// turns, fully or only about axis 1 — is the turn cut-out: above |turn rate| ≥ turn_cutout_rate the
// torques are zero (kBoth) or M1 is (kAxis1). sgn has a dead band: sgn(x) = 0 for |x| ≤ deadband (a real
// relay's threshold; 0 gives the book's sgn with sgn 0 = 0).
// Signals: reads e1, e2 [rad], α', β' [rad/s], turn rate [rad/s]; writes M1, M2 [N m], clipped to
// ±torque_limit_Nm. Pure functions, O(1), no state, no heap.
// Sampled-data check (check_gyro_vertical_correction, control period T): angle feedback makes precession
// at (c + f)/H per radian, kept ≤ 0.5/T; the viscous rows close a gyroscopic loop α' → β' → α' of gain
// d1 d2/H², kept ≤ 0.5 (it is an algebraic loop in the precession theory: Δ = H² + d1 d2).
// Tests: tests/unit/gyro_instrument_laws_test.cpp (each row's sign and value, cut-out, dead band, limits,
// checks); tests/oracle/gyro_vertical_test.cpp (closed loop against (12.41)-(12.49)).
// Docs: docs/models/gyro-vertical.md#firmware-law
#pragma once

#include <cmath>
#include <cstdint>

#include "firmware/control/config_check.hpp"

namespace gyrostab::firmware {

enum class TurnCutout : std::uint8_t {
  kBoth,   // both torques off while turning (the book's "fully")
  kAxis1,  // only M1 off (the book's "only about axis 1")
};

struct GyroVerticalCorrectionParams {
  double H{0.5};                 // spin momentum the law assumes (for the sampled checks) [N m s]
  double c1{0.0}, c2{0.0};       // row 1 [N m/rad]
  double d1{0.0}, d2{0.0};       // row 2 [N m s/rad]
  double r1{0.0}, r2{0.0};       // row 3 [N m]
  double f1{0.0}, f2{0.0};       // row 4 [N m/rad]
  double g1{0.0}, g2{0.0};       // row 5 [N m]
  double rate_deadband{0.0};     // sgn dead band of row 3 [rad/s]
  double tilt_deadband{0.0};     // sgn dead band of row 5 [rad]
  double torque_limit_Nm{0.1};   // |M1|, |M2| ≤ this [N m]
  double turn_cutout_rate{0.0};  // cut-out threshold on |turn rate|; 0: never [rad/s]
  TurnCutout cutout{TurnCutout::kBoth};
};

struct CorrectionSignals {
  double e1{0.0};         // α − α_L, erection sensor about axis 1 [rad]
  double e2{0.0};         // β − β_L, erection sensor about axis 2 [rad]
  double alpha_rate{0.0};  // α' [rad/s]
  double beta_rate{0.0};   // β' [rad/s]
  double turn_rate{0.0};   // vehicle turn rate (cut-out input) [rad/s]
};

struct CorrectionTorques {
  double M1{0.0};  // [N m]
  double M2{0.0};  // [N m]
  bool cut_out{false};  // the turn cut-out removed torque this call
  bool limited{false};  // a torque was clipped to ±torque_limit_Nm
};

// sgn with a dead band: 0 for |x| ≤ band.
constexpr double sgn_deadband(double x, double band) {
  return x > band ? 1.0 : (x < -band ? -1.0 : 0.0);
}

// The five rows of (12.35), each (M1, M2) [N m]. O(1).
inline CorrectionTorques pendulous_row(const GyroVerticalCorrectionParams& p, const CorrectionSignals& s) {
  return {-p.c1 * s.e1, -p.c2 * s.e2};
}
inline CorrectionTorques viscous_row(const GyroVerticalCorrectionParams& p, const CorrectionSignals& s) {
  return {-p.d1 * s.alpha_rate, -p.d2 * s.beta_rate};
}
inline CorrectionTorques coulomb_row(const GyroVerticalCorrectionParams& p, const CorrectionSignals& s) {
  return {-p.r1 * sgn_deadband(s.alpha_rate, p.rate_deadband), -p.r2 * sgn_deadband(s.beta_rate, p.rate_deadband)};
}
inline CorrectionTorques linear_correction_row(const GyroVerticalCorrectionParams& p, const CorrectionSignals& s) {
  return {-p.f1 * s.e2, p.f2 * s.e1};
}
inline CorrectionTorques relay_correction_row(const GyroVerticalCorrectionParams& p, const CorrectionSignals& s) {
  return {-p.g1 * sgn_deadband(s.e2, p.tilt_deadband), p.g2 * sgn_deadband(s.e1, p.tilt_deadband)};
}

// The sum of the five rows, the turn cut-out, the torque limit. O(1).
inline CorrectionTorques gyro_vertical_correction(const GyroVerticalCorrectionParams& p, const CorrectionSignals& s) {
  const CorrectionTorques rows[] = {pendulous_row(p, s), viscous_row(p, s), coulomb_row(p, s),
                                    linear_correction_row(p, s), relay_correction_row(p, s)};
  CorrectionTorques out;
  for (const CorrectionTorques& r : rows) {
    out.M1 += r.M1;
    out.M2 += r.M2;
  }
  const double turn = s.turn_rate < 0.0 ? -s.turn_rate : s.turn_rate;
  if (p.turn_cutout_rate > 0.0 && turn >= p.turn_cutout_rate) {
    out.cut_out = out.M1 != 0.0 || (p.cutout == TurnCutout::kBoth && out.M2 != 0.0);
    out.M1 = 0.0;
    if (p.cutout == TurnCutout::kBoth) out.M2 = 0.0;
  }
  const double L = p.torque_limit_Nm;
  if (out.M1 > L || out.M1 < -L || out.M2 > L || out.M2 < -L) out.limited = true;
  out.M1 = out.M1 > L ? L : (out.M1 < -L ? -L : out.M1);
  out.M2 = out.M2 > L ? L : (out.M2 < -L ? -L : out.M2);
  return out;
}

// Start-up check for control period T [s]. O(1).
inline ConfigCheck check_gyro_vertical_correction(const GyroVerticalCorrectionParams& p, double T) {
  auto nonneg = [](double x) { return std::isfinite(x) && x >= 0.0; };
  if (!(std::isfinite(p.H) && p.H > 0.0)) return ConfigCheck::refused("gyro vertical: H must be finite and > 0", p.H);
  if (!(nonneg(p.c1) && nonneg(p.c2) && nonneg(p.d1) && nonneg(p.d2) && nonneg(p.r1) && nonneg(p.r2) &&
        nonneg(p.f1) && nonneg(p.f2) && nonneg(p.g1) && nonneg(p.g2))) {
    return ConfigCheck::refused("gyro vertical: every (12.35) coefficient must be finite and >= 0");
  }
  if (!(nonneg(p.rate_deadband) && nonneg(p.tilt_deadband) && nonneg(p.turn_cutout_rate))) {
    return ConfigCheck::refused("gyro vertical: dead bands and the cut-out rate must be finite and >= 0");
  }
  if (!(std::isfinite(p.torque_limit_Nm) && p.torque_limit_Nm > 0.0)) {
    return ConfigCheck::refused("gyro vertical: torque_limit_Nm must be finite and > 0", p.torque_limit_Nm);
  }
  if (!(std::isfinite(T) && T > 0.0)) return ConfigCheck::refused("gyro vertical: control period must be > 0", T);
  const double angle_gain_max = 0.5 * p.H / T;  // (c + f)/H · T ≤ 0.5
  const double g1 = p.c1 + p.f2, g2 = p.c2 + p.f1;
  if (!(g1 <= angle_gain_max && g2 <= angle_gain_max)) {
    return ConfigCheck::refused("gyro vertical: (c + f) T / H > 0.5, the sampled correction oscillates",
                                g1 > g2 ? g1 : g2, 0.0, angle_gain_max);
  }
  if (!(p.d1 * p.d2 <= 0.5 * p.H * p.H)) {
    return ConfigCheck::refused("gyro vertical: d1 d2 / H^2 > 0.5, the sampled viscous rows oscillate",
                                p.d1 * p.d2, 0.0, 0.5 * p.H * p.H);
  }
  return ConfigCheck::accepted();
}

}  // namespace gyrostab::firmware
