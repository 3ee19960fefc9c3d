// Gyro vertical (gyro horizon) on a moving vehicle: a rotor with its axis near the vertical in a two-gimbal
// suspension, erected by a pendulous torque and by the torquers of a correction law (the firmware,
// firmware/control/gyro_vertical_correction.hpp), in the frame that turns with the vehicle's track.
//
// Book: Magnus §12.3 (docs/models/gyro-vertical.md): the torque table (12.35), errors in accelerated flight
// (12.36)-(12.42) and in a level turn (12.43)-(12.51); built on the master equation (10.22) (§10.2,
// sim/models/gyro_in_rotating_frame.hpp).
// Frame (the book's "123" vertical): axis 1 forward along the track, axis 2 to the right, axis 3 down (the
// rotor axis); α = roll-plane tilt of the rotor axis (about axis 1), β = pitch-plane tilt (about axis 2),
// both relative to the geocentric vertical of the frame. A right turn at rate ω has Ω3 = +ω (the book's
// "ω > 0 right turn" of (12.43)). Frame rates come from the vehicle generator's track trihedron
// T = (forward, left, up) as Ω = (Ω_T1, −Ω_T2, −Ω_T3), and likewise f.
// Apparent vertical (the plumb line of the specific force f = a_abs − g_grav, frame axes):
//   α_L = atan2(f2, −f3),  β_L = atan2(−f1, −f3)       (small: (12.43) α_L ≈ vω/g; (12.36) tanβ_L = −b/g)
// Torques (M1 about axis 1, M2 about axis 2), the rows of (12.35) that are physics of the instrument:
//   row 1, pendulous rotor case (CoM below the pivot):  −c (α − α_L),      −c (β − β_L)
//   row 2, viscous bearing friction:                     −d1 α',            −d2 β'
//   row 3, Coulomb bearing friction:                     −r1 sgn α',        −r2 sgn β'
//   + the torquer commands M1, M2 of the correction law (all five rows, firmware).
// Row 3 is stick-slip by default (friction_model kStickSlip, sim/drives/gimbal_bearings.hpp, decided once per
// step in begin_step): an axis whose net other torque stays within r is held, so the erection stops inside
// the dead zone of Fig. 12.12 — with the linear correction the band |f2 e1| ≤ r2, |f1 e2| ≤ r1 ((11.16)-(11.18)
// with the correction in place of c) — instead of creeping through it. kSmooth keeps r sat(α'/ε): viscous r/ε
// below ε, a creep of the order of the torque/(r/ε), for comparison only.
// Full form: (10.22) with these torques. Precession form (A = B = 0, the book's (12.35)-(12.51)): the rates
// from gyro_frame_precession_rates (viscous rows solved exactly); Coulomb friction is refused there (the
// reduced form cannot resolve sticking — use the full form).
// [derived] Nutation hidden by the precession theory (docs/models/gimbal-gyro.md#precession-model-p0):
// rows 4-5 are circulatory forces. For A = B, z = α + iβ, the full form is
//   A z'' + (d − iH) z' + (Hω + c − i f) z = 0      (d = d1 = d2);
// its roots sum to (−d + iH)/A, so with the precession root's real part −δ (δ = f/H) the nutation root has
// real part ≈ δ − d/A: without bearing damping the nutation GROWS at the correction rate δ. The instrument
// needs d/A > δ (tests/oracle/gyro_vertical_test.cpp); d shifts the precession decay by d(Hω + c)/(fH)
// relative. The erection sensor (liquid level on the rotor case) reads the tilt from the apparent vertical,
// e = (α − α_L, β − β_L): what the pendulous torque and every correction law act on ((12.37), (12.44)).
//
// State x = [α (rad), β (rad), α' (rad/s), β' (rad/s)] — relative to the frame. Precession form: x[2], x[3]
// are unused (kept 0); rates() computes the rates.
// Parameters (SI): GyroFrameParams A, B [kg m²], H [N m s]; c pendulous moment m g s [N m/rad]; d1, d2
// [N m s/rad]; r1, r2 [N m]; friction_model; stick_rate v_st [rad/s] (stick-slip: Karnopp's dead band);
// ε = coulomb_rate [rad/s] (smooth: below it the Coulomb torque is linear, a viscous r/ε — not physical).
// Inputs: FrameInputs (Ω, Ω', f over the step), torquer commands M1, M2 [N m] (zero-order hold).
// Assumptions: the book's — small angles, constant H, c constant (the load-factor change of the pendulous
// torque in a banked turn is neglected, as in (12.44)); the gimbal (kinematic) error of §1.1 is not modelled.
// Oracle: tests/oracle/gyro_vertical_test.cpp — steady-turn equilibrium z_G (12.47), resonance at ω = −ω^P,
// the δ = 0 and astatic limits (12.48)-(12.49), the deceleration response (12.41)-(12.42), linear-correction
// decay (corrected pairing, see firmware/control/gyro_vertical_correction.hpp), full vs precession form;
// tests/oracle/gimbal_stick_slip_test.cpp — the plant's dead zone (stuck inside the band, erects outside it,
// the smooth model's creep).
// Docs: docs/models/gyro-vertical.md#the-gyro-vertical
#pragma once

#include <algorithm>
#include <cmath>

#include "sim/drives/gimbal_bearings.hpp"
#include "sim/models/gyro_in_rotating_frame.hpp"

namespace gyrostab::models {

struct GyroVerticalParams {
  GyroFrameParams gyro{2e-3, 2e-3, 0.5};
  double c{2.5e-3};           // pendulous moment m g s, row 1 [N m/rad]
  double d1{0.0}, d2{0.0};    // viscous bearing friction, row 2 [N m s/rad]
  double r1{0.0}, r2{0.0};    // Coulomb bearing friction, row 3 [N m]
  drives::CoulombModel friction_model{drives::CoulombModel::kStickSlip};
  double stick_rate{1e-9};    // v_st, stick-slip dead band [rad/s]
  double coulomb_rate{1e-4};  // ε of sat(α'/ε), smooth model only [rad/s]
  InstrumentFidelity fidelity{InstrumentFidelity::kFull};

  // nullptr if usable, else why not (scene validation).
  const char* invalid_reason() const {
    if (const char* why = gyro_frame_invalid_reason(gyro, fidelity, c, d1, d2)) return why;
    const auto fin = [](double v) { return std::isfinite(v); };
    if (!(fin(r1) && r1 >= 0.0 && fin(r2) && r2 >= 0.0)) return "r1, r2 must be finite and >= 0";
    if (!(fin(coulomb_rate) && coulomb_rate > 0.0)) return "coulomb_rate must be finite and > 0";
    if (!(fin(stick_rate) && stick_rate > 0.0)) return "stick_rate must be finite and > 0";
    if (fidelity == InstrumentFidelity::kPrecession && (r1 > 0.0 || r2 > 0.0))
      return "Coulomb friction (r1, r2) needs the full form: the precession form cannot resolve sticking";
    return nullptr;
  }
};

struct GyroVerticalInputs {
  FrameInputs frame{};  // frame motion over the step (book axes: forward, right, down)
  double M1{0.0};       // torquer command about axis 1 [N m]
  double M2{0.0};       // torquer command about axis 2 [N m]
};

// Apparent-vertical angles (α_L, β_L) of the specific force f in book axes (forward, right, down) [rad].
struct ApparentVertical {
  double alpha_L{0.0};
  double beta_L{0.0};
};
inline ApparentVertical apparent_vertical(const dynamics::Vec3& f) {
  return {std::atan2(f.y(), -f.z()), std::atan2(-f.x(), -f.z())};
}

class GyroVertical {
 public:
  static constexpr int kStateSize = 4;
  using State = Eigen::Matrix<double, 4, 1>;
  // The state's components, by name.
  static constexpr int kAlpha = 0, kBeta = 1, kAlphaRate = 2, kBetaRate = 3;

  explicit GyroVertical(const GyroVerticalParams& p = {})
      : p_(p), bearings_(p.r1, p.r2, p.stick_rate),
        stick_slip_(p.friction_model == drives::CoulombModel::kStickSlip &&
                    p.fidelity == InstrumentFidelity::kFull && bearings_.active()) {}

  GyroVerticalInputs inputs{};  // held between steps

  const GyroVerticalParams& params() const { return p_; }

  static State make_state(double alpha, double beta, double alpha_rate = 0.0, double beta_rate = 0.0) {
    State x;
    x << alpha, beta, alpha_rate, beta_rate;
    return x;
  }

  void derivative(double t, const State& x, State& dx) const {
    const FrameSample w = inputs.frame.at(t);
    double M1s, M2s;
    static_torques(w, x, M1s, M2s);
    const auto coulomb = [this](double alpha_rate, double beta_rate, double& F1, double& F2) {
      if (stick_slip_) {
        F1 = -bearings_.torque(0);
        F2 = -bearings_.torque(1);
      } else {
        F1 = p_.r1 * sat(alpha_rate / p_.coulomb_rate);
        F2 = p_.r2 * sat(beta_rate / p_.coulomb_rate);
      }
    };
    gyro_frame_derivative(p_.gyro, p_.fidelity, w, x, M1s, M2s, p_.d1, p_.d2, dx, coulomb);
  }
  void project(State&) const {}

  // Stick-slip (sim/dynamics/step_start.hpp): holds a stuck gimbal (its rate set to 0) and fixes row 3's
  // torques for [t, t + h] from the net torques (10.22) at the step start, without friction.
  void begin_step(double t, double h, State& x) const {
    if (!stick_slip_) return;
    bearings_.begin_step(h, x[kAlphaRate], x[kBetaRate], [&] {
      const FrameSample w = inputs.frame.at(t);
      double M1s, M2s, a1, a2;
      static_torques(w, x, M1s, M2s);
      gyro_frame_accelerations(p_.gyro, w, x[0], x[1], x[2], x[3], M1s - p_.d1 * x[2], M2s - p_.d2 * x[3], a1, a2);
      return drives::AxisLoads{{p_.gyro.A * a1, p_.gyro.B * a2}, {p_.gyro.A, p_.gyro.B}};
    });
  }
  // The bearings of the current step (stuck flags, held torques); stick-slip only.
  const drives::GimbalBearings& bearings() const { return bearings_; }
  bool stick_slip() const { return stick_slip_; }

  // (α', β') at time t [rad/s]: the state's (full) or the precession solution's.
  void rates(double t, const State& x, double& alpha_rate, double& beta_rate) const {
    gyro_frame_rates(*this, p_.fidelity, t, x, alpha_rate, beta_rate);
  }

  // The erection sensor: tilt of the rotor axis from the apparent vertical (α − α_L, β − β_L) [rad].
  void erection_signal(double t, const State& x, double& e1, double& e2) const {
    const ApparentVertical L = apparent_vertical(inputs.frame.at(t).f);
    e1 = x[0] - L.alpha_L;
    e2 = x[1] - L.beta_L;
  }

 private:
  static double sat(double v) { return std::clamp(v, -1.0, 1.0); }
  // Rows 1 and the torquers: the rate-independent torques [N m].
  void static_torques(const FrameSample& w, const State& x, double& M1s, double& M2s) const {
    const ApparentVertical L = apparent_vertical(w.f);
    M1s = -p_.c * (x[0] - L.alpha_L) + inputs.M1;
    M2s = -p_.c * (x[1] - L.beta_L) + inputs.M2;
  }

  GyroVerticalParams p_;
  // The integrators hold the model const; the step's friction is a function of the step-start state and
  // the held inputs (like them, set between steps), so re-integrating from a saved state reproduces it.
  mutable drives::GimbalBearings bearings_;
  bool stick_slip_;
};

}  // namespace gyrostab::models
