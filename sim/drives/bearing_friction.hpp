// Bearing friction of a gimbal axis with stick-slip: Coulomb + viscous, optional Stribeck, and Karnopp's
// stick model made exact for a fixed-step loop (Magnus §11.2.2, Coulomb friction (11.6)-(11.10); a smoothed
// sgn would need a tiny step, docs/models/drives.md#bearing-friction).
//
//   slipping (|v| ≥ v_st):  τ_f = −τ_k(v) sgn v − b v,   τ_k(v) = τ_c + (τ_s − τ_c) e^{−(v/v_S)²}  (v_S = 0: τ_c)
//   stuck    (|v| < v_st and |τ_a| ≤ τ_s):  τ_f = −τ_a, the joint is held: the caller sets v = 0
//   breakaway (|v| < v_st and |τ_a| > τ_s): τ_f = −τ_k(0) sgn τ_a − b v
// τ_a is the net torque on the axis from everything else (motor through the gear, loads, gyroscopic and
// gravity terms), τ_s the breakaway (static) level, τ_c the sliding level.
//
// Why this does not chatter at a fixed step h. The classic failure: a slipping joint decelerates through
// zero inside a step, lands at −a h, the friction flips, and v rattles around zero (or the dead band v_st
// has to be wider than the largest velocity change per step, which makes the stuck test sloppy). Here the
// friction is given the axis inertia J, and the step is the time-stepping (Moreau / backward-Euler) answer:
// if the slip friction would carry v through zero within the step (v + h(τ_a + τ_f)/J has the other sign),
//   - and |τ_a| ≤ τ_s: the joint stops inside the step and stays, so the step's friction is the one that
//     lands v exactly on zero at the step end, τ_f = −τ_a − J v/h (between the sliding and the static
//     level, the time average of the two); the next step finds |v| < v_st and holds it;
//   - and |τ_a| > τ_s (the joint reverses): the friction is split at the stopping time s* = J v/(F − τ_a)
//     into −F before it and +τ_k(0) sgn v after it (the step average).
// With an exact J and τ_a constant over the step (a pure inertia) the joint lands on zero to rounding and
// never changes sign; then v_st only has to cover rounding and the drift of τ_a within the step. Without J
// (inertia ≤ 0) there is no landing, and v_st must exceed the largest |Δv| in a step, (τ_s + |τ_a|) h/J.
//
// Parameters: τ_c ≥ 0, τ_s ≥ τ_c [N m]; b ≥ 0 [N m s/rad]; v_st > 0 [rad/s]; v_S ≥ 0 [rad/s] (0: off).
// Stateless: the stuck state is |v| < v_st, which the hold keeps at exactly 0. The viscous part is explicit
// (torque from the step-start speed): stable for h < 2J/b (gimbal_drive.hpp adds the back-EMF to b).
// Test: tests/oracle/gimbal_drive_test.cpp (stuck exactly under a ramp below breakaway, slip above, finite-time
// stop at J v0/τ_c with no sign change, Coulomb nutation decay (11.6)-(11.9) at a 1 ms step).
// Docs: docs/models/drives.md#bearing-friction
#pragma once

#include <cmath>

namespace gyrostab::drives {

struct BearingFrictionParams {
  double coulomb{0.0};            // τ_c, sliding friction level [N m]
  double breakaway{0.0};          // τ_s, static friction level (≥ τ_c) [N m]
  double viscous{0.0};            // b [N m s/rad]
  double stick_velocity{1e-5};    // v_st, Karnopp dead band [rad/s]
  double stribeck_velocity{0.0};  // v_S, Stribeck velocity [rad/s]; 0: no Stribeck (τ_k = τ_c)
};

struct FrictionTorque {
  double torque{0.0};  // τ_f on the axis, constant over the step [N m]
  bool stuck{false};   // joint held: τ_f = −τ_a, and the caller must set the axis rate to 0 before the step
};

class BearingFriction {
 public:
  static const char* check(const BearingFrictionParams& p) {
    if (!(p.coulomb >= 0.0 && std::isfinite(p.coulomb))) return "bearing friction: coulomb must be >= 0 N m";
    if (!(p.breakaway >= p.coulomb && std::isfinite(p.breakaway)))
      return "bearing friction: breakaway must be >= coulomb (N m)";
    if (!(p.viscous >= 0.0 && std::isfinite(p.viscous))) return "bearing friction: viscous must be >= 0 N m s/rad";
    if (!(p.stick_velocity > 0.0 && std::isfinite(p.stick_velocity)))
      return "bearing friction: stick_velocity must be > 0 rad/s";
    if (!(p.stribeck_velocity >= 0.0 && std::isfinite(p.stribeck_velocity)))
      return "bearing friction: stribeck_velocity must be >= 0 rad/s";
    return nullptr;
  }

  explicit BearingFriction(const BearingFrictionParams& p = {}) : p_(p) {}

  const BearingFrictionParams& params() const { return p_; }

  // Whether v lies in the dead band (the joint is at rest or about to be held).
  bool in_dead_band(double v) const { return std::fabs(v) < p_.stick_velocity; }

  // Sliding friction level τ_k(v) ≥ 0 [N m].
  double kinetic(double v) const {
    if (p_.stribeck_velocity == 0.0) return p_.coulomb;
    const double r = v / p_.stribeck_velocity;
    return p_.coulomb + (p_.breakaway - p_.coulomb) * std::exp(-r * r);
  }

  // Friction over the next step of length h [s], given the axis rate v [rad/s], the net other torque τ_a
  // [N m] (held over the step) and the axis inertia J [kg m²] (≤ 0: unknown, no landing).
  FrictionTorque torque(double v, double applied, double inertia, double h) const {
    if (in_dead_band(v)) {
      if (std::fabs(applied) <= p_.breakaway) return {-applied, true};
      return {-kinetic(0.0) * sign(applied) - p_.viscous * v, false};
    }
    const double s = sign(v);
    const double F = kinetic(v) * s + p_.viscous * v;  // friction = −F
    if (inertia > 0.0 && h > 0.0) {
      const double v_next = v + h * (applied - F) / inertia;
      if (v_next * s <= 0.0) {  // v reaches zero inside this step
        if (std::fabs(applied) <= p_.breakaway) return {-applied - inertia * v / h, false};
        // Reversal: −F until v = 0 at s* = J v/(F − τ_a) (∈ (0, h]), then sliding the other way.
        const double s_stop = inertia * v / (F - applied);
        return {(-F * s_stop + kinetic(0.0) * s * (h - s_stop)) / h, false};
      }
    }
    return {-F, false};
  }

 private:
  static double sign(double x) { return x > 0.0 ? 1.0 : (x < 0.0 ? -1.0 : 0.0); }

  BearingFrictionParams p_;
};

}  // namespace gyrostab::drives
