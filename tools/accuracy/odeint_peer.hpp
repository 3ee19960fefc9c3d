// Peer: Boost.Odeint (Debian libboost-dev 1.74, header-only), integrating the study problem's right-hand
// side with the state as std::array<double, N> (odeint's default range algebra: what its examples use).
//
// Settings (docs/accuracy.md):
//   odeint-rk4     runge_kutta4, fixed step h = tick / substeps, do_step per step: the same classical RK4
//                  tableau as ours, so the difference is the library's overhead, not the method;
//   odeint-dopri5  controlled runge_kutta_dopri5 (make_controlled, abs = rel = tol), driven by try_step.
// Inputs switch at every tick (zero-order hold): the fixed-step stepper steps from tick to tick (the grid is
// aligned); the adaptive one is reset() at every tick boundary (its first-same-as-last derivative would
// otherwise carry the previous tick's input into the next step), its last step of a tick is cut to land on
// the boundary, and the step size it had reached is carried into the next tick as the first trial step.
#pragma once

#include <algorithm>
#include <array>
#include <boost/numeric/odeint.hpp>
#include <cmath>
#include <string>

#include "tools/accuracy/study_problem.hpp"
#include "tools/accuracy/study_run.hpp"

namespace gyrostab::tools::accuracy {

// The problem's right-hand side in odeint's system signature.
template <class Model>
struct OdeintSystem {
  static constexpr int N = Model::kStateSize;
  using State = typename Model::State;
  const CountedModel<Model>* model;
  void operator()(const std::array<double, N>& x, std::array<double, N>& dx, double t) const {
    const State xs = Eigen::Map<const State>(x.data());
    State ds;
    model->derivative(t, xs, ds);
    Eigen::Map<State>(dx.data()) = ds;
  }
};

template <class Problem>
IntegrationOutcome integrate_odeint_rk4(Problem& p, int substeps, Trajectory<typename Problem::State>& out) {
  namespace odeint = boost::numeric::odeint;
  using Model = typename Problem::Model;
  constexpr int N = Problem::kStateSize;
  CountedModel<Model> model{&p.model()};
  const OdeintSystem<Model> sys{&model};
  odeint::runge_kutta4<std::array<double, N>> stepper;
  std::array<double, N> x;
  Eigen::Map<typename Problem::State>(x.data()) = p.initial_state();
  out[0] = Eigen::Map<const typename Problem::State>(x.data());
  const std::int64_t n = p.ticks();
  const double h = 1e-9 * static_cast<double>(p.tick_ns()) / substeps;
  for (std::int64_t k = 0; k < n; ++k) {
    p.set_tick(k);
    const double t0 = tick_time(k, p.tick_ns());
    for (int j = 0; j < substeps; ++j) stepper.do_step(sys, x, t0 + j * h, h);
    out[static_cast<std::size_t>(k + 1)] = Eigen::Map<const typename Problem::State>(x.data());
  }
  IntegrationOutcome o;
  o.ok = out.back().allFinite();
  if (!o.ok) o.error = "non-finite state";
  o.rhs_evaluations = model.evaluations;
  o.steps = n * substeps;
  return o;
}

template <class Problem>
IntegrationOutcome integrate_odeint_dopri5(Problem& p, double tolerance, Trajectory<typename Problem::State>& out) {
  namespace odeint = boost::numeric::odeint;
  using Model = typename Problem::Model;
  constexpr int N = Problem::kStateSize;
  using S = std::array<double, N>;
  CountedModel<Model> model{&p.model()};
  const OdeintSystem<Model> sys{&model};
  auto stepper = odeint::make_controlled(tolerance, tolerance, odeint::runge_kutta_dopri5<S>());
  S x;
  Eigen::Map<typename Problem::State>(x.data()) = p.initial_state();
  out[0] = Eigen::Map<const typename Problem::State>(x.data());
  const std::int64_t n = p.ticks();
  const double tick = 1e-9 * static_cast<double>(p.tick_ns());
  double dt = tick;  // first trial: one whole tick
  IntegrationOutcome o;
  std::int64_t steps = 0, rejections = 0;
  for (std::int64_t k = 0; k < n; ++k) {
    p.set_tick(k);
    stepper.reset();
    double t = tick_time(k, p.tick_ns());
    const double t1 = tick_time(k + 1, p.tick_ns());
    // Land on t1: the remainder below 1e-12 of a tick is the rounding of t, not a step.
    while (t1 - t > 1e-12 * tick) {
      const bool cut = dt >= t1 - t;
      double h = cut ? t1 - t : dt;
      if (stepper.try_step(sys, x, t, h) == odeint::success) {
        ++steps;
        // h now holds the step odeint suggests next; a step cut to the boundary says little about the
        // natural step, so the larger of the two is kept.
        dt = cut ? std::max(dt, h) : h;
      } else {
        dt = h;  // reduced by the controller
        if (++rejections > 100 * (n + 1) || !(dt > 1e-15 * tick)) {
          o.error = "dopri5 step size underflow at tick " + std::to_string(k);
          o.rhs_evaluations = model.evaluations;
          for (std::int64_t j = k + 1; j <= n; ++j) out[static_cast<std::size_t>(j)].setConstant(std::nan(""));
          return o;
        }
      }
    }
    out[static_cast<std::size_t>(k + 1)] = Eigen::Map<const typename Problem::State>(x.data());
  }
  o.ok = out.back().allFinite();
  if (!o.ok) o.error = "non-finite state";
  o.rhs_evaluations = model.evaluations;
  o.steps = steps;
  return o;
}

}  // namespace gyrostab::tools::accuracy
