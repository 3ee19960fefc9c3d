// Peer: SUNDIALS CVODE (Debian libsundials-dev 6.4.1), variable-order variable-step, integrating the study
// problem's right-hand side through its C callback.
//
// Settings (what a careful user would pick; docs/accuracy.md):
//   BDF    CV_BDF with the default Newton iteration and a dense direct linear solver, Jacobian by CVODE's
//          own difference quotients (the plants have no analytic Jacobian);
//   Adams  CV_ADAMS with the fixed-point nonlinear solver (CVODE's recommendation for non-stiff problems);
//   scalar tolerances rtol = atol = tol (the plants' states are O(0.01 … 1) in SI; H is constant).
// Inputs switch at every tick (zero-order hold), a discontinuity of the right-hand side: CVODE is restarted
// at every tick boundary (CVodeReInit at t_k from the state reached, stop time t_{k+1}), as its manual asks
// for discontinuities, rather than integrating across them with stale history. Its step-size and order
// selection starts afresh each tick (order 1, CVODE's own initial-step estimate).
#pragma once

#include <cstdint>
#include <string>

#include "tools/accuracy/study_problem.hpp"
#include "tools/accuracy/study_run.hpp"

namespace gyrostab::tools::accuracy {

enum class CvodeMethod { kBdf, kAdams };

// The non-template core (tools/accuracy/cvode_peer.cpp): one CVODE instance for an n-state problem.
class CvodeSolver {
 public:
  using Rhs = void (*)(double t, const double* x, double* dx, void* context);

  CvodeSolver(int n, CvodeMethod method, double tolerance, Rhs rhs, void* context);
  ~CvodeSolver();
  CvodeSolver(const CvodeSolver&) = delete;
  CvodeSolver& operator=(const CvodeSolver&) = delete;

  bool ok() const { return error_.empty(); }
  const std::string& error() const { return error_; }
  // Restart at (t0, x0) and integrate to t1 (stop time: never evaluates beyond t1); x receives x(t1).
  bool advance(double t0, double t1, double* x);
  std::int64_t steps() const { return total_steps_; }

 private:
  void init(CvodeMethod method, double tolerance);
  static int callback(double t, void* y, void* ydot, void* self);
  void fail(const char* what, int flag);

  int n_;
  Rhs rhs_;
  void* context_;
  void* sunctx_{nullptr};
  void* mem_{nullptr};
  void* y_{nullptr};
  void* matrix_{nullptr};
  void* linear_solver_{nullptr};
  void* nonlinear_solver_{nullptr};
  std::int64_t total_steps_{0};
  std::string error_;
};

const char* cvode_method_name(CvodeMethod m);
const char* sundials_version();

template <class Problem>
IntegrationOutcome integrate_cvode(Problem& p, CvodeMethod method, double tolerance,
                                   Trajectory<typename Problem::State>& out) {
  using Model = typename Problem::Model;
  using State = typename Problem::State;
  CountedModel<Model> model{&p.model()};
  const CvodeSolver::Rhs rhs = [](double t, const double* x, double* dx, void* ctx) {
    const auto* m = static_cast<const CountedModel<Model>*>(ctx);
    const State xs = Eigen::Map<const State>(x);
    State ds;
    m->derivative(t, xs, ds);
    Eigen::Map<State> result(dx);
    result = ds;
  };
  IntegrationOutcome o;
  CvodeSolver solver(Problem::kStateSize, method, tolerance, rhs, &model);
  if (!solver.ok()) {
    o.error = solver.error();
    return o;
  }
  State x = p.initial_state();
  out[0] = x;
  const std::int64_t n = p.ticks();
  for (std::int64_t k = 0; k < n; ++k) {
    p.set_tick(k);
    if (!solver.advance(tick_time(k, p.tick_ns()), tick_time(k + 1, p.tick_ns()), x.data())) {
      o.error = solver.error() + " at tick " + std::to_string(k);
      for (std::int64_t j = k + 1; j <= n; ++j) out[static_cast<std::size_t>(j)].setConstant(std::nan(""));
      o.rhs_evaluations = model.evaluations;
      return o;
    }
    out[static_cast<std::size_t>(k + 1)] = x;
  }
  o.ok = x.allFinite();
  if (!o.ok) o.error = "non-finite state";
  o.rhs_evaluations = model.evaluations;
  o.steps = solver.steps();
  return o;
}

}  // namespace gyrostab::tools::accuracy
