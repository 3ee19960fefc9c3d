// Power gyro stabilizer control law: the two-axis stabilization loops (14.19) with the rate damping that
// damps the nutation, or the single-axis back-EMF voltage law (14.27); with the start-up gain check against
// the Hurwitz conditions (14.25) / (14.30) that refuses gains making the loop unstable and says by how much.
//
// Book: Magnus §14.3, (14.19)-(14.30) (docs/models/power-stabilizer.md).
//
// Torque mode (PowerStabilizerOutput::kTorque; current-controlled torque motors on both gimbal axes):
//   M1^K = −k1 β − d1 α',     M2^K = +k2 α − d2 β'                          (14.19) + rate damping
// With the plant A α'' + H β' = M1^S + M1^K, B β'' − H α' = M2^S + M2^K this is the book's (14.20), with
// characteristic equation (14.23)
//   AB λ⁴ + (A d2 + B d1) λ³ + (H² + d1 d2) λ² + H (k1 + k2) λ + k1 k2 = 0.
// In the check, d1, d2 are the total viscous damping: the commanded rate feedback plus the passive bearing
// damping the configuration declares (bearing_d1, bearing_d2). Without damping the nutation is self-excited
// (Re λ ≈ (k1 + k2)/(2H) − (A d2 + B d1)/(2AB) for small d and k, derived from (14.23)) although the
// precession theory (14.24) predicts λ = −k/H; and the gains are bounded above by the damping, (14.25):
//   D2 = (H² + d1 d2)(A d2 + B d1) − AB H (k1 + k2) > 0,    D3 = H (k1 + k2) D2 − (A d2 + B d1)² k1 k2 > 0.
// Along the configured gain ratio, k → σ k, both hold iff σ < σ_max (the gain margin reported):
//   σ_max = H K P S / (AB H² K² + S² k1 k2),   K = k1 + k2,  P = H² + d1 d2,  S = A d2 + B d1;
// for k1 = k2 = k:  k < k_max = 2 H P S / (4 AB H² + S²)   (reference case S2 of
// docs/models/power-stabilizer.md: 28.12 N m/rad).
// Steady state under constant disturbances (14.21): α0 = −M20^S/k2, β0 = M10^S/k1 — the stiffness is k, and
// the torque limit must exceed the largest disturbance to be balanced (else the gyro precesses away).
//
// Voltage mode (kBackEmfVoltage; the book's single-axis stabilizer, one geared DC motor on axis 1,
// (14.26)-(14.30); axis 2 carries no loop):
//   commanded terminal voltage   u_cmd = −r β − d_c α'                     → motor1_voltage_V
// The motor itself (plant: sim/models/power_stabilizer.hpp, BackEmfMotor) turns it into
//   M1^K = s (u_cmd − d_emf α') = s u,   u = −r β − d α',   d = d_emf + d_c            (14.26)-(14.27)
// i.e. the book's d is the motor's back-EMF coefficient (incl. the gear ratio κ) plus any electronic rate
// feedback d_c; with d_c = 0 the damping is the back-EMF alone — the book's point that it can make a damper
// unnecessary. With A including the reflected motor inertia κ²I the characteristic equation is (14.29)
//   λ [AB λ³ + B d s λ² + H² λ + H r s] = 0,   stable (up to the neutral α, λ = 0) iff r < H d / A  (14.30).
// With bearing damping (D1 = s d + bearing_d1, d2 = bearing_d2) the cubic generalises to
//   AB λ³ + (A d2 + B D1) λ² + (H² + D1 d2) λ + H r s = 0,   r_max = (A d2 + B D1)(H² + D1 d2)/(AB H s),
// which is H d / A when the bearings are frictionless. The back-EMF damping acts even when u_cmd saturates.
//
// Signals (the power stabilizer's frames: tools/devices/power_stabilizer/power_stabilizer_signals.toml,
// docs/icd/power_stabilizer.md): reads alpha_rad = α, beta_rad = β, alpha_rate_rad_s = α', beta_rate_rad_s =
// β' (rates relative to the carrier) — nothing else. Writes motor1_torque_Nm, motor2_torque_Nm,
// motor1_voltage_V, motor2_voltage_V (the unused mode's values are 0) and its own status bits
// (PowerStabilizerStatusBit, 16-20; the other status bits and the header — tick, time, sequence, sensor
// tick — are left to the caller). Refused gains ⇒ the safe command (firmware/fault/safe_state.hpp) with
// kGainsRefused on every tick.
// Sampling: the Hurwitz check is for the continuous loop. At 1 kHz with a zero-order hold and one tick of
// latency (≈ a pure delay τ = 1.5 ms) the nutation's phase lag ω_N τ is 0.084 rad for the S2 stabilizer
// (ω_N = 56 rad/s); solving (14.23) with the loop terms × e^{−λτ} moves its nutation root from −0.16249 to
// −0.16216 1/s and the bound k_max from 28.1250 to 28.1253 (the delayed damping and the delayed stiffness
// nearly cancel). Keep ω_N τ ≪ 1; otherwise design with the sampled loop.
// Elastic platform (14.38): the book's back-EMF term uses the platform rate φ'; the motor model produces it
// itself, so with d_c = 0 nothing changes here; a non-zero d_c acts on alpha_rate_rad_s (the gimbal's α').
// Resources: stateless (the configuration and the check are fixed at construction); compute() is O(1), no
// heap, no exceptions, no I/O. Oracle: tests/oracle/power_stabilizer_test.cpp.
// Docs: docs/models/power-stabilizer.md
#pragma once

#include <cmath>
#include <cstdint>

#include "firmware/control/hurwitz.hpp"
#include "firmware/control/saturation.hpp"
#include "firmware/fault/safe_state.hpp"
#include "gyrostab_signals/power_stabilizer_frames.hpp"

namespace gyrostab::firmware {

enum class PowerStabilizerOutput : std::uint8_t {
  kTorque,          // M1^K, M2^K → motor1_torque_Nm, motor2_torque_Nm (torque-controlled drives)
  kBackEmfVoltage,  // u_cmd → motor1_voltage_V (voltage-driven geared motor, back-EMF damping)
};

// ActuatorFrame::status bits of this law (bits 16-31 are the control laws', msg/fault_bits.hpp).
enum class PowerStabilizerStatusBit : std::uint32_t {
  kTorque1Saturated = 1u << 16,  // |M1^K| was clipped to torque_limit_Nm[0] this tick
  kTorque2Saturated = 1u << 17,  // |M2^K| was clipped to torque_limit_Nm[1] this tick
  kVoltageSaturated = 1u << 18,  // |u_cmd| was clipped to voltage_limit_V this tick
  kGainsRefused = 1u << 19,      // the start-up gain check failed: the safe command is output
  kNonFiniteCommand = 1u << 20,  // a sensor signal read was NaN/Inf: zero command this tick
};
constexpr std::uint32_t bit(PowerStabilizerStatusBit b) {
  return static_cast<std::uint32_t>(b);
}
inline constexpr std::uint32_t kPowerStabilizerStatusMask = 0x1Fu << 16;

struct PowerStabilizerConfig {
  // What the controller assumes about the plant; used by the gain check only.
  double A{1.0};           // inertia about the outer axis 1, incl. reflected motor inertia κ²I [kg m²]
  double B{0.8};           // inertia about the inner axis 2 [kg m²]
  double H{50.0};          // rotor spin momentum [N m s]
  double bearing_d1{0.0};  // known passive viscous damping, outer bearing [N m s/rad]
  double bearing_d2{0.0};  // known passive viscous damping, inner bearing [N m s/rad]

  PowerStabilizerOutput output{PowerStabilizerOutput::kTorque};

  // Torque mode: (14.19) + rate damping. Defaults: reference case S2 (docs/models/power-stabilizer.md).
  double k1{20.0};                                         // M1^K per rad of β [N m/rad]
  double k2{20.0};                                         // M2^K per rad of α [N m/rad]
  double d1{0.5};                                          // commanded rate damping, axis 1 [N m s/rad]
  double d2{0.5};                                          // commanded rate damping, axis 2 [N m s/rad]
  double torque_limit_Nm[2]{100.0, 100.0};                 // |M^K| saturation per axis (1, 2) [N m]

  // Voltage mode: (14.26)-(14.27).
  double r{10.0};                // u_cmd per rad of β [V/rad]
  double d_c{0.0};               // u_cmd per rad/s of α' (electronic damping, adds to d_emf) [V s/rad]
  double s{2.0};                 // motor torque per volt at the gimbal, κ k_t / R_winding [N m/V]
  double d_emf{0.25};            // motor back-EMF per gimbal rate, incl. gear, κ k_e [V s/rad]
  double voltage_limit_V{24.0};  // |u_cmd| saturation [V]
};

enum class GainCheckVerdict : std::uint8_t {
  kAccepted,
  kInvalidPlant,  // A, B, H not > 0 and finite, or bearing damping < 0
  kInvalidGain,   // a gain not finite, a damping < 0, or s ≤ 0
  kInvalidLimit,  // a saturation limit not > 0 and finite
  kNoStiffness,   // k1 ≤ 0 or k2 ≤ 0 (torque), r ≤ 0 (voltage): the λ⁰ coefficient is not > 0
  kNoDamping,     // the λ³ (torque) / λ² (voltage) coefficient is 0: the nutation is self-excited
  kHurwitzD2,     // D2 ≤ 0: gains too high for the damping (14.25) / r ≥ H d / A (14.30)
  kHurwitzD3,     // D3 ≤ 0: gains too high for the damping (14.25)
};

struct GainCheck {
  bool accepted{false};
  GainCheckVerdict verdict{GainCheckVerdict::kInvalidPlant};
  const char* reason{""};      // static text: the condition and the book equation
  double D2{0.0};              // (14.25) D^II, or (14.30) D^II in voltage mode
  double D3{0.0};              // (14.25) D^III (torque mode; 0 in voltage mode)
  double gain_scale_max{0.0};  // largest σ with (σ k1, σ k2) / σ r stable: the gain margin (> 1 iff stable)
  double k1_max{0.0};          // torque mode: σ_max k1, the bound along the configured ratio [N m/rad]
  double k2_max{0.0};          // torque mode: σ_max k2 [N m/rad]
  double k_max_equal{0.0};     // torque mode: largest stable k1 = k2 = k for these d [N m/rad]
  double r_max{0.0};           // voltage mode: (14.30) bound on r [V/rad]
};

namespace detail {

inline bool finite(double x) {
  return std::isfinite(x);
}
inline bool positive_finite(double x) {
  return std::isfinite(x) && x > 0.0;
}
inline bool non_negative_finite(double x) {
  return std::isfinite(x) && x >= 0.0;
}

inline GainCheck refuse(GainCheck g, GainCheckVerdict v, const char* reason) {
  g.accepted = false;
  g.verdict = v;
  g.reason = reason;
  return g;
}

inline GainCheck check_torque_loops(const PowerStabilizerConfig& c) {
  GainCheck g;
  if (!finite(c.k1) || !finite(c.k2) || !non_negative_finite(c.d1) || !non_negative_finite(c.d2)) {
    return refuse(g, GainCheckVerdict::kInvalidGain, "k1, k2 must be finite and d1, d2 finite and >= 0");
  }
  if (!positive_finite(c.torque_limit_Nm[0]) || !positive_finite(c.torque_limit_Nm[1])) {
    return refuse(g, GainCheckVerdict::kInvalidLimit, "torque_limit_Nm must be > 0 and finite on both axes");
  }
  const double d1 = c.d1 + c.bearing_d1, d2 = c.d2 + c.bearing_d2;
  const double S = c.A * d2 + c.B * d1;  // λ³ coefficient of (14.23)
  const double P = c.H * c.H + d1 * d2;  // λ² coefficient
  const double AB = c.A * c.B;
  g.k_max_equal = 2.0 * c.H * P * S / (4.0 * AB * c.H * c.H + S * S);
  const HurwitzResult h = hurwitz_quartic(AB, S, P, c.H * (c.k1 + c.k2), c.k1 * c.k2);
  g.D2 = h.D2;
  g.D3 = h.D3;
  if (c.k1 > 0.0 && c.k2 > 0.0) {
    const double K = c.k1 + c.k2;
    g.gain_scale_max = c.H * K * P * S / (AB * c.H * c.H * K * K + S * S * c.k1 * c.k2);
    g.k1_max = g.gain_scale_max * c.k1;
    g.k2_max = g.gain_scale_max * c.k2;
  }
  if (!(c.k1 > 0.0) || !(c.k2 > 0.0)) {
    return refuse(
        g, GainCheckVerdict::kNoStiffness,
        "k1 > 0 and k2 > 0 needed: the coefficient k1 k2 of (14.23) must be > 0 (else the gyro drifts"
        " or diverges)");
  }
  if (!(S > 0.0)) {
    return refuse(
        g, GainCheckVerdict::kNoDamping,
        "no damping: A d2 + B d1 = 0 makes the lambda^3 coefficient of (14.23) zero, the nutation is"
        " self-excited for every k > 0 (14.23)-(14.24)");
  }
  if (!(h.D2 > 0.0)) {
    return refuse(
        g, GainCheckVerdict::kHurwitzD2,
        "D2 = (H^2 + d1 d2)(A d2 + B d1) - A B H (k1 + k2) <= 0 (14.25): gains too high for the damping,"
        " the nutation grows; see k1_max, k2_max");
  }
  if (!(h.D3 > 0.0)) {
    return refuse(
        g, GainCheckVerdict::kHurwitzD3,
        "D3 = H (k1 + k2) D2 - (A d2 + B d1)^2 k1 k2 <= 0 (14.25): gains too high for the damping, the"
        " nutation grows; see k1_max, k2_max");
  }
  g.accepted = true;
  g.verdict = GainCheckVerdict::kAccepted;
  g.reason = "accepted: (14.25) D2 > 0 and D3 > 0";
  return g;
}

inline GainCheck check_voltage_law(const PowerStabilizerConfig& c) {
  GainCheck g;
  if (!finite(c.r) || !finite(c.d_c) || !non_negative_finite(c.d_emf) || !positive_finite(c.s)) {
    return refuse(g, GainCheckVerdict::kInvalidGain, "r, d_c must be finite, d_emf finite and >= 0, s > 0");
  }
  if (!positive_finite(c.voltage_limit_V)) {
    return refuse(g, GainCheckVerdict::kInvalidLimit, "voltage_limit_V must be > 0 and finite");
  }
  const double d = c.d_emf + c.d_c;
  const double D1 = c.s * d + c.bearing_d1, d2 = c.bearing_d2;  // viscous torque per rad/s on axes 1, 2
  const double a3 = c.A * c.B, a2 = c.A * d2 + c.B * D1, a1 = c.H * c.H + D1 * d2;
  if (D1 > 0.0 && a2 > 0.0) g.r_max = a2 * a1 / (a3 * c.H * c.s);
  const HurwitzResult h = hurwitz_cubic(a3, a2, a1, c.H * c.r * c.s);
  g.D2 = h.D2;
  if (c.r > 0.0) g.gain_scale_max = g.r_max / c.r;
  if (!(c.r > 0.0)) {
    return refuse(g, GainCheckVerdict::kNoStiffness,
                  "r > 0 needed: the coefficient H r s of (14.29) must be > 0 (r = 0 leaves beta neutral)");
  }
  if (!(D1 > 0.0) || !(a2 > 0.0)) {
    return refuse(
        g, GainCheckVerdict::kNoDamping,
        "no damping: d = d_emf + d_c must make s d + bearing_d1 > 0; with the lambda^2 coefficient of"
        " (14.29) zero the oscillation is undamped or grows");
  }
  if (!(h.D2 > 0.0)) {
    return refuse(g, GainCheckVerdict::kHurwitzD2,
                  "D2 = H B s (H d - A r) <= 0 (14.30): r >= H d / A, the nutation grows; see r_max");
  }
  g.accepted = true;
  g.verdict = GainCheckVerdict::kAccepted;
  g.reason = "accepted: (14.30) r < H d / A";
  return g;
}

}  // namespace detail

// The start-up gain check: plant parameters, gains, limits, then the Hurwitz conditions of the configured
// mode. The bounds (k_max_equal, k1_max, k2_max, gain_scale_max, r_max) are filled whenever the plant
// parameters are valid, also for refused gains. O(1).
inline GainCheck check_power_stabilizer_gains(const PowerStabilizerConfig& c) {
  using detail::non_negative_finite;
  using detail::positive_finite;
  if (!positive_finite(c.A) || !positive_finite(c.B) || !positive_finite(c.H) ||
      !non_negative_finite(c.bearing_d1) || !non_negative_finite(c.bearing_d2)) {
    return detail::refuse(GainCheck{}, GainCheckVerdict::kInvalidPlant,
                          "plant: A, B, H must be > 0 and finite, bearing_d1, bearing_d2 >= 0");
  }
  return c.output == PowerStabilizerOutput::kTorque ? detail::check_torque_loops(c)
                                                    : detail::check_voltage_law(c);
}

// The laws themselves, unsaturated and unchecked (pure functions of the signals; what compute() applies).
struct StabilizationTorques {
  double M1{0.0};  // M1^K on the outer axis [N m]
  double M2{0.0};  // M2^K on the inner axis [N m]
};
// (14.19) + rate damping: M1^K = −k1 β − d1 α', M2^K = k2 α − d2 β'.
constexpr StabilizationTorques stabilization_torques(const PowerStabilizerConfig& c, double alpha,
                                                     double beta, double alpha_rate, double beta_rate) {
  return {-c.k1 * beta - c.d1 * alpha_rate, c.k2 * alpha - c.d2 * beta_rate};
}
// (14.27), terminal voltage: u_cmd = −r β − d_c α' (the motor adds −d_emf α' itself) [V].
constexpr double back_emf_voltage(const PowerStabilizerConfig& c, double beta, double alpha_rate) {
  return -c.r * beta - c.d_c * alpha_rate;
}

class PowerStabilizerLoops {
 public:
  explicit PowerStabilizerLoops(const PowerStabilizerConfig& config)
      : config_(config), check_(check_power_stabilizer_gains(config)) {}

  const PowerStabilizerConfig& config() const { return config_; }
  const GainCheck& gain_check() const { return check_; }
  bool armed() const { return check_.accepted; }

  // One controller tick: the command from the sensor frame (see the header for the fields).
  void compute(const msg::power_stabilizer::SensorFrame& in, msg::power_stabilizer::ActuatorFrame& out) const {
    out.status &= ~kPowerStabilizerStatusMask;
    out.motor1_torque_Nm = 0.0;
    out.motor2_torque_Nm = 0.0;
    out.motor1_voltage_V = 0.0;
    out.motor2_voltage_V = 0.0;
    if (!check_.accepted) {
      command_safe_state(out);
      out.status |= bit(PowerStabilizerStatusBit::kGainsRefused);
      return;
    }
    const double alpha = in.alpha_rad, beta = in.beta_rad;
    const double alpha_rate = in.alpha_rate_rad_s, beta_rate = in.beta_rate_rad_s;
    if (!std::isfinite(alpha) || !std::isfinite(beta) || !std::isfinite(alpha_rate) ||
        !std::isfinite(beta_rate)) {
      out.status |= bit(PowerStabilizerStatusBit::kNonFiniteCommand);
      return;
    }
    if (config_.output == PowerStabilizerOutput::kTorque) {
      const StabilizationTorques m = stabilization_torques(config_, alpha, beta, alpha_rate, beta_rate);
      out.motor1_torque_Nm = saturate(m.M1, config_.torque_limit_Nm[0], out.status,
                                      PowerStabilizerStatusBit::kTorque1Saturated);
      out.motor2_torque_Nm = saturate(m.M2, config_.torque_limit_Nm[1], out.status,
                                      PowerStabilizerStatusBit::kTorque2Saturated);
    } else {
      out.motor1_voltage_V = saturate(back_emf_voltage(config_, beta, alpha_rate), config_.voltage_limit_V,
                                      out.status, PowerStabilizerStatusBit::kVoltageSaturated);
    }
  }

 private:
  // clip_symmetric (saturation.hpp), with this law's flag.
  static double saturate(double x, double limit, std::uint32_t& status, PowerStabilizerStatusBit flag) {
    const Clipped c = clip_symmetric(x, limit);
    if (c.clipped) status |= bit(flag);
    return c.value;
  }

  PowerStabilizerConfig config_;
  GainCheck check_;
};

}  // namespace gyrostab::firmware
