// A plant ẋ = f(x, u) under a memoryless law u = law(x), linearised at x0 by central differences — the plant
// through its own derivative, the law through the firmware's own step (probed with the signals the plant gives
// at x): A = ∂f/∂x, B = ∂f/∂u, K = ∂law/∂x at (x0, u0 = law(x0)). The `_predicted_sampled` figures of the
// devices whose model is not written as matrices start here (docs/sampled-data.md), then restrict_state_feedback
// and sampled_loop_roots. Steps: h on the states, hu on the inputs (a model linear in its inputs takes any hu).
// Host only (dynamic matrices): for schemas and reports, never the hot loop.
#pragma once

#include <type_traits>

#include <Eigen/Core>

namespace gyrostab::analysis {

struct StateFeedbackLinearisation {
  Eigen::MatrixXd A, B, K;
  Eigen::VectorXd u0;
};

// f(x, u) returns ẋ (any Eigen vector of x's size), law(x) the command (any Eigen vector).
template <class State, class F, class Law>
StateFeedbackLinearisation linearise_state_feedback(const State& x0, F&& f, Law&& law, double h, double hu) {
  const auto u0 = law(x0);
  using Input = std::decay_t<decltype(u0)>;
  const auto n = x0.size(), p = u0.size();
  StateFeedbackLinearisation r{Eigen::MatrixXd(n, n), Eigen::MatrixXd(n, p), Eigen::MatrixXd(p, n), u0};
  for (Eigen::Index i = 0; i < n; ++i) {
    State xp = x0, xm = x0;
    xp[i] += h;
    xm[i] -= h;
    r.A.col(i) = (f(xp, u0) - f(xm, u0)) / (2.0 * h);
    r.K.col(i) = (law(xp) - law(xm)) / (2.0 * h);
  }
  for (Eigen::Index j = 0; j < p; ++j) {
    Input up = u0, um = u0;
    up[j] += hu;
    um[j] -= hu;
    r.B.col(j) = (f(x0, up) - f(x0, um)) / (2.0 * hu);
  }
  return r;
}

}  // namespace gyrostab::analysis
