// Classical fourth-order Runge-Kutta, fixed step, templated on the model's state size.
//
// A Model provides
//   static constexpr int kStateSize;  using State = Eigen::Matrix<double, kStateSize, 1>;
//   void derivative(double t, const State& x, State& dx) const;
//   void project(State& x) const;     // e.g. quaternion renormalisation; may do nothing
// and optionally begin_step(t, h, x) (step_start.hpp: decisions held over the step, e.g. stick-slip).
//
// Amplification factor on y' = λy: R(z) = 1 + z + z²/2 + z³/6 + z⁴/24, z = hλ. On an undamped mode
// (z = iωh) |R| < 1: RK4 damps oscillations numerically, by 1.8e-10 per second for a 200 Hz nutation at
// 1 kHz (docs/models/integrators.md). step_validation.hpp refuses such steps.
// Docs: docs/models/integrators.md#methods
#pragma once

#include <Eigen/Core>

#include "sim/dynamics/step_start.hpp"

namespace gyrostab::dynamics {

template <class Model>
class Rk4 {
 public:
  using State = typename Model::State;
  static constexpr const char* kName = "rk4";

  explicit Rk4(const Model& model) : model_(model) {}

  void step(double t, double h, State& x) {
    begin_step(model_, t, h, x);
    model_.derivative(t, x, k1_);
    tmp_.noalias() = x + (0.5 * h) * k1_;
    model_.derivative(t + 0.5 * h, tmp_, k2_);
    tmp_.noalias() = x + (0.5 * h) * k2_;
    model_.derivative(t + 0.5 * h, tmp_, k3_);
    tmp_.noalias() = x + h * k3_;
    model_.derivative(t + h, tmp_, k4_);
    x.noalias() += (h / 6.0) * (k1_ + 2.0 * (k2_ + k3_) + k4_);
    model_.project(x);
  }

 private:
  const Model& model_;
  State k1_, k2_, k3_, k4_, tmp_;
};

}  // namespace gyrostab::dynamics
