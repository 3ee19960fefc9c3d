// The step-start hook of the fixed-step integrators: a model may define
//   void begin_step(double t, double h, State& x) const;
// which every integrator calls before it evaluates the step, with the step's start time and length. It is
// where a decision that must hold over the whole step is taken — the stick-slip friction of the gimbal
// bearings (sim/drives/gimbal_bearings.hpp): whether an axis is held (its rate set to 0) and the friction
// torque held over the step. A per-stage decision would put the discontinuity inside the Runge-Kutta
// stages, which is what loses the method's order and makes a stuck axis chatter.
// The hook must depend only on (t, h, x) and the model's held inputs, never on history, so that a
// re-integration from a saved state (sim/analysis/half_step_window.hpp) lands on the run bit for bit.
// Docs: docs/models/integrators.md#methods
#pragma once

namespace gyrostab::dynamics {

template <class Model, class State>
inline void begin_step(const Model& model, double t, double h, State& x) {
  if constexpr (requires { model.begin_step(t, h, x); }) model.begin_step(t, h, x);
}

}  // namespace gyrostab::dynamics
