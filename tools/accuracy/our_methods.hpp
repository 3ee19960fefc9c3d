// Ours: the project's fixed-step integrators (sim/dynamics) driven exactly as a scene drives them — a
// dynamics::SubstepDriver taking `substeps` equal steps per controller tick, time from the integer tick.
//   gyro-exponential   exact damped gyroscopic (nutation) flow + exponential midpoint (2nd order); needs the
//                      model's gyroscopic_pair()
//   rk4                classical Runge-Kutta (4th order)
//   implicit-midpoint  simplified Newton, difference-quotient Jacobian unless the model has one (2nd order)
//   held-input-adams4  Adams-Bashforth 4 whose history survives the tick-held input jumps (one right-hand
//                      side per step); needs the model's input-affine split (held_input_adams.hpp)
#pragma once

#include <cmath>
#include <string>
#include <string_view>

#include "sim/dynamics/gyroscopic_exponential.hpp"
#include "sim/dynamics/held_input_adams.hpp"
#include "sim/dynamics/implicit_midpoint.hpp"
#include "sim/dynamics/rk4.hpp"
#include "sim/dynamics/substepping.hpp"
#include "tools/accuracy/study_problem.hpp"
#include "tools/accuracy/study_run.hpp"

namespace gyrostab::tools::accuracy {

template <template <class> class Integrator, class Problem>
IntegrationOutcome integrate_with(Problem& p, int substeps, Trajectory<typename Problem::State>& out) {
  using Model = CountedModel<typename Problem::Model>;
  const Model model{&p.model()};
  Integrator<Model> integrator(model);
  dynamics::SubstepDriver<Integrator<Model>> driver(integrator, p.tick_ns(), substeps);
  typename Problem::State x = p.initial_state();
  out[0] = x;
  const std::int64_t n = p.ticks();
  for (std::int64_t k = 0; k < n; ++k) {
    p.set_tick(k);
    driver.advance_tick(k, x);
    out[static_cast<std::size_t>(k + 1)] = x;
  }
  IntegrationOutcome o;
  o.ok = x.allFinite();
  if (!o.ok) o.error = "non-finite state";
  o.rhs_evaluations = model.evaluations;
  o.steps = n * substeps;
  return o;
}

template <class Problem>
constexpr bool has_gyroscopic_pair =
    requires(const typename Problem::Model& m, const typename Problem::State& x) { m.gyroscopic_pair(x); };

template <class Problem>
constexpr bool has_held_input_split = dynamics::HeldInputModel<typename Problem::Model>;

// Which of our methods apply to the problem's model.
template <class Problem>
bool our_method_applies(std::string_view method) {
  if (method == "gyro-exponential") return has_gyroscopic_pair<Problem>;
  if (method == "held-input-adams4") return has_held_input_split<Problem>;
  return method == "rk4" || method == "implicit-midpoint";
}

// Order of accuracy (for the half-step error estimate's Richardson factor).
inline int our_method_order(std::string_view method) { return method == "rk4" ? 4 : 2; }

template <class Problem>
IntegrationOutcome integrate_ours(std::string_view method, Problem& p, int substeps,
                                  Trajectory<typename Problem::State>& out) {
  if (method == "rk4") return integrate_with<dynamics::Rk4>(p, substeps, out);
  if (method == "implicit-midpoint") return integrate_with<dynamics::ImplicitMidpoint>(p, substeps, out);
  if constexpr (has_gyroscopic_pair<Problem>) {
    if (method == "gyro-exponential") return integrate_with<dynamics::GyroscopicExponential>(p, substeps, out);
  }
  if constexpr (has_held_input_split<Problem>) {
    if (method == "held-input-adams4") return integrate_with<dynamics::HeldInputAdams4>(p, substeps, out);
  }
  IntegrationOutcome o;
  o.error = "method " + std::string(method) + " does not apply to this plant";
  return o;
}

}  // namespace gyrostab::tools::accuracy
