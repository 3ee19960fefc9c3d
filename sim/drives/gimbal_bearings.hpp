// Coulomb friction in the two bearings of a gimbal suspension, with stick-slip: the bearing model of the
// drives (bearing_friction.hpp, Karnopp's stick model with the Moreau landing, Magnus §11.2.2 (11.6)-(11.10))
// applied to both gimbal axes of a gyro whose axes are coupled by the gyroscopic torques H β', H α'.
//
// Why both axes are decided together, once per integrator step (sim/dynamics/step_start.hpp). The net torque
// on axis 1 contains −H β', so whether axis 1 may stick depends on whether axis 2 is held. Per step:
//   1. the model gives each axis's net torque τ_a without bearing friction, and its inertia J, at the step
//      start (AxisLoads);
//   2. BearingFriction decides per axis: stuck (|v| < v_st, |τ_a| ≤ r), breakaway, slipping, or a landing
//      on v = 0 inside the step;
//   3. the held axes get v = 0, the loads are taken again at that state (the gyroscopic torque of a rate
//      that was just zeroed is gone), and each held axis gets τ_f = −τ_a exactly — or, if its load now
//      exceeds r, it breaks away instead. A stuck pair under static torques therefore has zero acceleration
//      to rounding: the gyro does not move while |τ_a,1| ≤ r1 and |τ_a,2| ≤ r2 (the dead zone of Fig. 12.12,
//      (11.16)-(11.18)), and the precession of a torque below friction stops instead of creeping.
// The torques are held over the step; within it a held axis can drift only by the change of its load over
// the step (frame motion, the other axis's acceleration), and the next step zeroes its rate again.
// The breakaway level is the sliding level r (the book's Coulomb law, no Stribeck); no viscous part (the
// models keep their own d1, d2 in τ_a).
//
// State: the held torques and stuck flags of the current step (set by begin_step, a function of the
// step-start state only). Parameters: r1, r2 [N m] ≥ 0 (0: that bearing has no Coulomb friction), v_st
// [rad/s] > 0, the Karnopp dead band (it must exceed the rate left after a landing: rounding plus the load's
// change over the step, ~ (ω_N h)² times the nutation rate amplitude). O(1), no heap.
// Test: tests/oracle/gimbal_stick_slip_test.cpp. Docs: docs/models/gimbal-gyro.md#coulomb-friction-stick-slip
#pragma once

#include <array>
#include <cmath>

#include "sim/drives/bearing_friction.hpp"

namespace gyrostab::drives {

// How a gimbal model applies its Coulomb rows r1, r2.
enum class CoulombModel {
  kStickSlip,  // GimbalBearings: held axes, exact dead zone (the book's Coulomb law)
  kSmooth,  // r v/sqrt(v² + ε²) (or r sat(v/ε)): viscous r/ε below ε — a creep, kept for comparison
};

// Net torque on each gimbal axis without its bearing friction [N m], and the axis inertia [kg m²].
struct AxisLoads {
  std::array<double, 2> torque{};
  std::array<double, 2> inertia{};
};

class GimbalBearings {
 public:
  GimbalBearings(double r1, double r2, double stick_rate)
      : r_{r1, r2},
        axis_{BearingFriction({.coulomb = r1, .breakaway = r1, .stick_velocity = stick_rate}),
              BearingFriction({.coulomb = r2, .breakaway = r2, .stick_velocity = stick_rate})} {}

  bool active() const { return r_[0] > 0.0 || r_[1] > 0.0; }

  // Decides the step [t, t + h]: may set rate1, rate2 (references into the state) to 0. `loads()` returns
  // AxisLoads at the current state; it is called while the held torques are 0.
  template <class Loads>
  void begin_step(double h, double& rate1, double& rate2, const Loads& loads) {
    torque_ = {0.0, 0.0};
    stuck_ = {false, false};
    double* rate[2] = {&rate1, &rate2};
    AxisLoads L = loads();
    std::array<double, 2> next{};
    std::array<bool, 2> hold{};
    for (int i = 0; i < 2; ++i) {
      if (r_[i] == 0.0) continue;
      const FrictionTorque f = axis_[i].torque(*rate[i], L.torque[i], L.inertia[i], h);
      next[i] = f.torque;
      hold[i] = f.stuck;
    }
    if (hold[0] || hold[1]) {
      for (int i = 0; i < 2; ++i)
        if (hold[i]) *rate[i] = 0.0;
      L = loads();
      for (int i = 0; i < 2; ++i) {
        if (!hold[i]) continue;
        if (std::fabs(L.torque[i]) <= r_[i]) {
          next[i] = -L.torque[i];
        } else {
          hold[i] = false;
          next[i] = -r_[i] * (L.torque[i] > 0.0 ? 1.0 : -1.0);
        }
      }
    }
    torque_ = next;
    stuck_ = hold;
  }

  double torque(int axis) const { return torque_[axis]; }  // τ_f held over the step [N m]
  bool stuck(int axis) const { return stuck_[axis]; }      // the axis is held this step
  double level(int axis) const { return r_[axis]; }        // r_i [N m]

 private:
  std::array<double, 2> r_;
  std::array<BearingFriction, 2> axis_;
  std::array<double, 2> torque_{};
  std::array<bool, 2> stuck_{};
};

}  // namespace gyrostab::drives
