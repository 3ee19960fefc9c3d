// The ship roll damper of Magnus §14.2 (sim/models/ship_roll_damper.hpp, (14.8)-(14.18)) in a sea: the wave
// moment E(t) evaluated at every integrator stage (no zero-order hold on E), the firmware's precession torque
// held over the tick and the precession brake acting as a viscous torque −brake β'. State as the model's:
// [φ (rad), β (rad), φ' (rad/s), β' (rad/s)]. Sea: anything with `double operator()(double t) const` [N m].
// One right-hand side for the scene's plant (ship_roll_damper_plant.hpp), the accuracy study and the
// benchmarks, so the study integrates the scene's plant operation for operation.
// Docs: docs/models/ship-roll-damper.md.
#pragma once

#include <cmath>

#include "sim/dynamics/damped_gyroscopic_flow.hpp"
#include "sim/models/ship_roll_damper.hpp"

namespace gyrostab::plants {

template <class Sea>
struct ShipInSeaOf {
  static constexpr int kStateSize = 4;
  using State = models::ShipRollDamper::State;
  mutable models::ShipRollDamper ship;
  const Sea* sea;
  double brake_Nms{0.0};   // controller's brake, on top of the bearing's own d2 in the model [N m s/rad]
  double command_Nm{0.0};  // precession torque [N m]

  void derivative(double t, const State& x, State& dx) const {
    ship.inputs.E = (*sea)(t);
    ship.inputs.M2 = command_Nm - brake_Nms * x[models::ShipRollDamper::kPrecessionRate];
    ship.derivative(t, x, dx);
  }
  void project(State&) const {}

  // The input-affine split for dynamics::HeldInputAdams4: g with the held torque and brake off, and their
  // part G(x) u = (command − brake β')/B on β'' (the same terms derivative() adds into M2).
  void derivative_without_inputs(double t, const State& x, State& g) const {
    ship.inputs.E = (*sea)(t);
    ship.inputs.M2 = 0.0;
    ship.derivative(t, x, g);
  }
  void add_held_inputs(const State& x, State& dx) const {
    dx[models::ShipRollDamper::kPrecessionRate] +=
        (command_Nm - brake_Nms * x[models::ShipRollDamper::kPrecessionRate]) / ship.params().total_B();
  }

  // The gyroscopic pair of (14.8) for dynamics::GyroscopicExponential (the accuracy study's variant; the scene
  // runs rk4): H cosβ coupling over I(β) = A − Q sin²β and B, viscous d1 and d2 + brake.
  dynamics::GyroscopicPair gyroscopic_pair(const State& x) const {
    const models::ShipRollDamperParams& p = ship.params();
    const double beta = x[models::ShipRollDamper::kPrecession];
    const double sb = std::sin(beta), cb = std::cos(beta);
    const double inertia = p.A - p.total_Q() * sb * sb;
    return {p.total_H() * cb / inertia, p.total_H() * cb / p.total_B(), p.d1 / inertia,
            (p.total_d2() + brake_Nms) / p.total_B()};
  }
};

}  // namespace gyrostab::plants
