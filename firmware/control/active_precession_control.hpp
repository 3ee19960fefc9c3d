// Active precession control of the ship roll damper: roll-rate feedback into the precession torque, a soft
// limit of the precession angle, braking before the hard end stops, torque saturation.
//
// Book: Magnus §14.2 (docs/models/ship-roll-damper.md), with the plant's large-angle coupling H cosβ (14.41):
//   A φ'' + d1 φ' + c φ + H cosβ β' = E(t),        B β'' + d2 β' + q β − H cosβ φ' = M2          (14.8)
// Practice (modern Seakeeper-type ship gyrostabilizers): the stabilizing torque is the gyroscopic H β' cosβ;
// the precession actuator shapes β' (more precession per roll rate than the passive brake allows), keeps β in
// its working range, and brakes the case before the end stops so that it does not slam into them.
//
// Sign (derived from (14.8), H > 0 by convention): the gyroscopic torque on the hull is −H cosβ β'. It
// opposes the roll rate (removes roll energy, power −H cosβ β' φ' < 0) iff β' has the SAME sign as φ' —
// so in this convention the law commands β' ∝ +φ', i.e. a case torque M2 = +k_r cosβ φ'. (It is "−φ'" only
// if one counts the reaction on the hull: the hull feels −H cosβ β' ∝ −φ'.) The passive case does the same
// by itself: B β'' + d2 β' = H φ' drives β' with φ'. A rotor spinning the other way is H < 0 here: both
// signs flip, so the Config must state H > 0 in the plant's convention.
//
// The law (signals of the ship roll damper's table: φ' = roll_rate_rad_s, β = precession_angle_rad,
// β' = precession_rate_rad_s; output M2 = precession_torque_Nm [N m]). With the
// gyroscopic drive on the case D = H cosβ φ' (the plant's term), the roll-rate feedback F = k_r cosβ φ',
// σ = sgn β, dz = max(0, |β| − β_soft) and the schedule g = clamp((β_soft − |β|)/w, 0, 1):
//   M_law   = F − d_c β' − k_c β − σ k_s dz − σ (1 − g) (max(0, σ F) + max(0, σ D))
//   braking toward the stop ahead (s = sgn β', δ = β_soft − s β, a_req = β'² / (2 max(δ, δ_min))):
//            starts when a_req ≥ a_b, then lasts until β' stops (or reverses)
//   M_brake = −s (B max(a_req, a_b) + max(0, s D))
//   M       = the more opposing (w.r.t. s) of M_law and M_brake while braking, else M_law; |M| ≤ M_max.
// Parts:
//   - roll-rate feedback F and precession damping d_c β': a rate servo β' → (k_r/d_c) cosβ φ' plus the
//     gyroscopic drive. Quasi-statically (B, q neglected) d_c β' = (H + k_r) cosβ φ', so the roll sees a
//     damping H (H + k_r) cos²β / d_c (passive: H²/d2). The cosβ matches the plant's coupling, which is what
//     makes the stability argument below exact for the large-angle coupling. An optional centring stiffness
//     k_c re-centres the case after a sustained heel (adds to the pendulous q).
//   - soft limit by gain scheduling: over the band w below β_soft the part of the roll-rate feedback that
//     pushes the case outward fades out (g: 1 → 0) and the outward part of the gyroscopic drive is
//     cancelled (0 → 1); at and beyond β_soft nothing pushes the case outward (inward pulls are kept), and a
//     restoring stiffness k_s — a term that grows with the distance beyond the limit — with the damping d_c
//     returns it, B β'' = −σ k_s dz − (d_c + d2) β' − q β. The torque is continuous in β (no chatter when
//     the case rides at the limit under a sustained drive).
//   - end stops: brake before the stop so that the case reaches the soft limit with zero rate. The envelope
//     |β'| = sqrt(2 a_b δ) is the fastest approach from which a deceleration a_b still stops the case at
//     β_soft; once on it, the law commands the constant deceleration a_req = β'²/(2δ) that stops exactly at
//     β_soft (on the parabola a_req stays constant: d/dt[β'²/(2δ)] = 0 when β'' = −s a_req), and never less
//     than a_b (so the case stops early rather than late when the sampled parabola is left), by the torque
//     B a plus the part of the gyroscopic drive that pushes toward the stop (cancelled; a drive that already
//     decelerates is left in). δ_min guards the division at and beyond the limit, where an outward rate v is
//     braked at v²/(2 δ_min), i.e. stopped within ≈ δ_min. The hard stop β_stop > β_soft is
//     the margin for what the saturated torque cannot hold (a drive H |φ'| above M_max − B a_b); the law
//     never engages the holding brake (precession_brake stays 0).
//   - saturation: |M| ≤ M_max (kAxis2TorqueSaturated).
// Stability argument (E = 0, plant (14.8) with the cosβ coupling, constant k_r > −H, d_c > 0, q + k_c > 0),
// for |β| ≤ β_soft − w (where g = 1 and the law is linear in the rates):
//   V = ½ A φ'² + ½ c φ² + m (½ B β'² + ½ (q + k_c) β²),   m = H / (H + k_r) > 0
//   V' = −d1 φ'² − m (d_c + d2) β'² + φ' β' cosβ (−H + m (H + k_r)) = −d1 φ'² − m (d_c + d2) β'² ≤ 0.
// The weight m makes the non-skew coupling (H in the roll equation, H + k_r in the precession equation)
// cancel, so the closed loop is the passive damper with H² replaced by H (H + k_r) (same characteristic
// equation, (14.11)-(14.18) hold with that substitution, and so does Hahnkamm's minimax choice of d_c).
// LaSalle: V' = 0 forces β' ≡ 0, then φ' constant, then φ = φ' = 0 and (q + k_c) β = 0 ⇒ β = 0:
// asymptotically stable, for every k_r ≥ 0, with no upper gain bound in continuous time. The braking
// override only ever makes M more opposed to β' (ΔM β' ≤ 0), so it can only lower V. In the band and beyond
// the argument is one of boundedness, not of a Lyapunov function: no torque pushes the case outward at
// |β| ≥ β_soft, and the spring-damper returns it (the scheduled removal of the outward pushes is not
// dissipative when the case moves inward). Not covered: torque saturation (the argument holds while |M| <
// M_max; the stops bound β regardless), the large-angle pendulous cross-term q sinφ (1 − cosβ) (third order),
// and sampling, which the check bounds (d_c T/B ≤ 0.5, sqrt((k_c + k_s)/B) T ≤ 0.5, sampled_loop_limits.hpp).
// Defaults: the constructed reference ship (docs/models/ship-roll-damper.md) with k_r = H and d_c ≈ 8.36e4 N
// m s/rad, the minimax d2 of (14.11) for H_eff² = H (H + k_r) = 2 H² (peak roll 1.036 × static, passive
// minimax 1.063 ×; computed from (14.11) off-line), limits ±60° soft / ±70° hard (the plant's default stops).
// State: the braking direction (one int). O(1), no heap. Tests: tests/unit/control_laws_test.cpp.
// Docs: docs/models/ship-roll-damper.md#firmware-laws
#pragma once

#include <cmath>

#include "firmware/control/config_check.hpp"
#include "firmware/control/sampled_loop_limits.hpp"
#include "firmware/control/saturation.hpp"
#include "firmware/math/deterministic_math.hpp"

namespace gyrostab::firmware {

struct ActivePrecessionParams {
  // What the law assumes about the plant (used by the braking feed-forward and the checks).
  double B{1.5e4};    // case + rotor inertia about axis 2 [kg m²]
  double H{1.018e6};  // rotor spin momentum, > 0 in the convention of (14.8) [N m s]
  // Gains.
  double roll_rate_gain{1.018e6};     // k_r: M2 per rad/s of φ' (× cosβ) [N m s/rad], ≥ 0
  double precession_damping{8.36e4};  // d_c: M2 per rad/s of β' [N m s/rad], > 0
  double centring_stiffness{0.0};     // k_c: M2 per rad of β [N m/rad], ≥ 0
  // Limits of the precession angle.
  double beta_soft{1.0471975511965976};        // soft limit β_soft (60°) [rad]
  double schedule_width{0.17453292519943295};  // w: band below β_soft where outward pushes fade (10°) [rad]
  double soft_stiffness{5.0e5};                // k_s beyond the soft limit [N m/rad]
  double beta_stop{1.2217304763960306};        // hard end stops of the plant (70°) [rad]
  double brake_deceleration{2.0};              // a_b: envelope deceleration [rad/s²]
  double brake_distance_floor{1e-3};           // δ_min: smallest distance used in a_req [rad]
  double torque_limit_Nm{2.0e5};               // M_max [N m]
};

struct ActivePrecessionState {
  int braking_direction{0};  // +1 / −1 while braking toward the + / − stop (until β' stops), 0 otherwise
};

struct ActivePrecessionInputs {
  double roll_rate{0.0};  // φ' [rad/s]
  double beta{0.0};       // β [rad]
  double beta_rate{0.0};  // β' [rad/s]
};

struct ActivePrecessionOutput {
  double torque_Nm{0.0};      // M2, after braking and saturation [N m]
  double law_torque_Nm{0.0};  // M_law, the scheduled law before braking and saturation (diagnostics) [N m]
  bool saturated{false};      // |M| was clipped to M_max
  bool beyond_soft_limit{false};  // |β| > β_soft
  bool scheduled{false};          // |β| > β_soft − w: the outward pushes are faded / cancelled
  bool braking{false};            // end-stop braking active this tick
};

// One control tick. Pure function of (params, state, inputs); updates the braking direction. O(1).
inline ActivePrecessionOutput active_precession_step(const ActivePrecessionParams& p,
                                                     ActivePrecessionState& st,
                                                     const ActivePrecessionInputs& in) {
  auto pos = [](double x) { return x > 0.0 ? x : 0.0; };
  ActivePrecessionOutput out;
  const double cb = math::cos(in.beta);
  const double drive = p.H * cb * in.roll_rate;                  // D, gyroscopic drive on the case [N m]
  const double feedback = p.roll_rate_gain * cb * in.roll_rate;  // F [N m]
  const double sigma = in.beta < 0.0 ? -1.0 : 1.0;
  const double abs_beta = sigma * in.beta;
  const double dz = pos(abs_beta - p.beta_soft);
  const double g_raw = (p.beta_soft - abs_beta) / p.schedule_width;
  const double g = g_raw >= 1.0 ? 1.0 : pos(g_raw);
  out.beyond_soft_limit = dz > 0.0;
  out.scheduled = g < 1.0;
  out.law_torque_Nm = feedback - p.precession_damping * in.beta_rate - p.centring_stiffness * in.beta -
                      sigma * p.soft_stiffness * dz -
                      sigma * (1.0 - g) * (pos(sigma * feedback) + pos(sigma * drive));
  double torque = out.law_torque_Nm;

  const double s = in.beta_rate > 0.0 ? 1.0 : (in.beta_rate < 0.0 ? -1.0 : 0.0);
  const int dir = static_cast<int>(s);
  if (dir == 0 || st.braking_direction != dir) st.braking_direction = 0;
  if (dir != 0) {
    const double v = s * in.beta_rate;
    const double distance = p.beta_soft - s * in.beta;  // to the soft limit ahead (≤ 0 beyond it) [rad]
    const double a_req =
        v * v / (2.0 * (distance > p.brake_distance_floor ? distance : p.brake_distance_floor));
    if (st.braking_direction == dir || a_req >= p.brake_deceleration) {
      st.braking_direction = dir;
      const double a_cmd = a_req > p.brake_deceleration ? a_req : p.brake_deceleration;
      const double brake = -s * (p.B * a_cmd + pos(s * drive));
      if ((s > 0.0 && brake < torque) || (s < 0.0 && brake > torque)) torque = brake;
      out.braking = true;
    }
  }
  const Clipped m = clip_symmetric(torque, p.torque_limit_Nm);
  out.torque_Nm = m.value;
  out.saturated = m.clipped;
  return out;
}

// Start-up check for control period T [s]: plant and gain signs, the limits' order
// 0 < δ_min < β_soft < β_stop < π/2, 0 < w ≤ β_soft, the braking authority B a_b < M_max, and the
// sampled-loop bounds. O(1).
inline ConfigCheck check_active_precession(const ActivePrecessionParams& p, double T) {
  auto finite = [](double x) { return std::isfinite(x); };
  if (!(finite(p.B) && p.B > 0.0)) return ConfigCheck::refused("active: B must be finite and > 0", p.B);
  if (!(finite(p.H) && p.H > 0.0)) {
    return ConfigCheck::refused("active: H must be finite and > 0 in the convention of (14.8)", p.H);
  }
  if (!(finite(p.roll_rate_gain) && p.roll_rate_gain >= 0.0)) {
    return ConfigCheck::refused("active: roll_rate_gain k_r must be finite and >= 0 (sign from (14.8))",
                                p.roll_rate_gain);
  }
  if (!(finite(p.precession_damping) && p.precession_damping > 0.0)) {
    return ConfigCheck::refused("active: precession_damping d_c must be > 0 (asymptotic stability needs it)",
                                p.precession_damping);
  }
  if (!(finite(p.centring_stiffness) && p.centring_stiffness >= 0.0) ||
      !(finite(p.soft_stiffness) && p.soft_stiffness >= 0.0)) {
    return ConfigCheck::refused("active: centring_stiffness and soft_stiffness must be finite and >= 0");
  }
  constexpr double kHalfPi = 1.5707963267948966;
  if (!(finite(p.beta_stop) && p.beta_stop > 0.0 && p.beta_stop < kHalfPi)) {
    return ConfigCheck::refused("active: beta_stop must lie in (0, pi/2)", p.beta_stop, 0.0, kHalfPi);
  }
  if (!(finite(p.beta_soft) && p.beta_soft > 0.0 && p.beta_soft < p.beta_stop)) {
    return ConfigCheck::refused("active: beta_soft must lie in (0, beta_stop)", p.beta_soft, 0.0,
                                p.beta_stop);
  }
  if (!(finite(p.schedule_width) && p.schedule_width > 0.0 && p.schedule_width <= p.beta_soft)) {
    return ConfigCheck::refused("active: schedule_width must lie in (0, beta_soft]", p.schedule_width, 0.0,
                                p.beta_soft);
  }
  if (!(finite(p.brake_distance_floor) && p.brake_distance_floor > 0.0 &&
        p.brake_distance_floor < p.beta_soft)) {
    return ConfigCheck::refused("active: brake_distance_floor must lie in (0, beta_soft)",
                                p.brake_distance_floor, 0.0, p.beta_soft);
  }
  if (!(finite(p.torque_limit_Nm) && p.torque_limit_Nm > 0.0)) {
    return ConfigCheck::refused("active: torque_limit_Nm must be finite and > 0", p.torque_limit_Nm);
  }
  const double a_max = p.torque_limit_Nm / p.B;
  if (!(finite(p.brake_deceleration) && p.brake_deceleration > 0.0 && p.brake_deceleration < a_max)) {
    return ConfigCheck::refused(
        "active: brake_deceleration a_b must lie in (0, torque_limit/B): the drive cannot brake the case "
        "harder",
        p.brake_deceleration, 0.0, a_max);
  }
  const double d_max = max_sampled_damping(p.B, T);
  if (!(p.precession_damping <= d_max)) {
    return ConfigCheck::refused("active: d_c T / B > 0.5, the sampled precession loop oscillates",
                                p.precession_damping, 0.0, d_max);
  }
  const double k_max = max_sampled_stiffness(p.B, T);
  if (!(p.centring_stiffness + p.soft_stiffness <= k_max)) {
    return ConfigCheck::refused(
        "active: sqrt((k_c + k_s)/B) T > 0.5, the soft limit is too stiff for the period",
        p.centring_stiffness + p.soft_stiffness, 0.0, k_max);
  }
  return ConfigCheck::accepted();
}

}  // namespace gyrostab::firmware
