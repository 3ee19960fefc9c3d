// The error estimate every `gyrostab run` report carries (report.json "error_estimate"), for plants without
// invariants to watch (forced, damped, controlled): a half-step comparison over a sampled window.
//
// During the run (allocation-free, a branch per tick outside the window): at the window's first tick the
// state is saved, and over its K ticks the inputs the plant held (zero-order hold) and the state reached.
// After the run, outside the timed loop: the window is integrated again from the saved state with the
// run's own integrator, once at the run's step — it must land on the run's states bit for bit, which proves
// the capture complete (`reproduces_run`) — and once at half the step. For a method of order p the run's
// error at each tick is estimated by Richardson's (x_h − x_{h/2}) · 2^p / (2^p − 1); the report gives its
// largest magnitude over the window per state. Deterministic (no clock): identical run to run. The report's
// JSON of the estimate: tools/loop/error_estimate_report.hpp.
// Limits: it estimates the error the integrator adds over the window (started from the run's own state),
// not the error accumulated before it; a window that the run does not reach is reported as such.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "sim/dynamics/substepping.hpp"

namespace gyrostab::analysis {

template <int N>
struct HalfStepEstimate {
  const char* integrator{""};
  int order{0};
  double step_s{0.0};
  double window_start_s{0.0};
  std::int64_t window_ticks{0};  // captured; 0: the run ended before the window
  bool reproduces_run{false};    // the re-integration at the run's step landed on the run's states bit for bit
  std::array<double, N> max_abs_error{};  // per state, Richardson-corrected
};

template <class Model, class Inputs>
class HalfStepWindow {
 public:
  using State = typename Model::State;
  static constexpr int N = Model::kStateSize;

  // Window [first_tick, first_tick + ticks); sized here, before the loop.
  HalfStepWindow(std::int64_t first_tick, std::int64_t ticks)
      : first_(std::max<std::int64_t>(first_tick, 0)),
        size_(std::max<std::int64_t>(ticks, 1)),
        inputs_(static_cast<std::size_t>(size_)),
        states_(static_cast<std::size_t>(size_)) {}

  // Just before the plant integrates `tick`, with the inputs it holds over the tick.
  void before_tick(std::int64_t tick, const State& x, const Inputs& in) {
    const std::int64_t i = tick - first_;
    if (i < 0 || i >= size_) return;
    if (i == 0) start_ = x;
    inputs_[static_cast<std::size_t>(i)] = in;
  }
  // Just after the plant integrated `tick`.
  void after_tick(std::int64_t tick, const State& x) {
    const std::int64_t i = tick - first_;
    if (i < 0 || i >= size_) return;
    states_[static_cast<std::size_t>(i)] = x;
    captured_ = i + 1;
  }

  // `apply(model, inputs)` sets a model copy's held inputs; `order` is the integrator's.
  template <template <class> class Integrator, class Apply>
  HalfStepEstimate<N> estimate(const Model& model, Apply apply, std::int64_t tick_ns, int substeps, int order) const {
    HalfStepEstimate<N> e;
    e.integrator = Integrator<Model>::kName;
    e.order = order;
    e.step_s = 1e-9 * static_cast<double>(tick_ns) / substeps;
    e.window_start_s = 1e-9 * static_cast<double>(first_ * tick_ns);
    e.window_ticks = captured_;
    if (captured_ == 0) return e;
    std::vector<State> at_h, at_half;
    integrate<Integrator>(model, apply, tick_ns, substeps, at_h);
    integrate<Integrator>(model, apply, tick_ns, 2 * substeps, at_half);
    bool same = true;
    std::array<double, N> worst{};
    for (std::int64_t i = 0; i < captured_; ++i) {
      const auto k = static_cast<std::size_t>(i);
      for (int c = 0; c < N; ++c) {
        same = same && at_h[k][c] == states_[k][c];
        worst[static_cast<std::size_t>(c)] = std::max(worst[static_cast<std::size_t>(c)], std::abs(at_h[k][c] - at_half[k][c]));
      }
    }
    const double richardson = std::ldexp(1.0, order) / (std::ldexp(1.0, order) - 1.0);
    for (int c = 0; c < N; ++c) e.max_abs_error[static_cast<std::size_t>(c)] = richardson * worst[static_cast<std::size_t>(c)];
    e.reproduces_run = same;
    return e;
  }

 private:
  template <template <class> class Integrator, class Apply>
  void integrate(const Model& model, Apply apply, std::int64_t tick_ns, int substeps, std::vector<State>& out) const {
    Model m = model;
    Integrator<Model> integ(m);
    dynamics::SubstepDriver<Integrator<Model>> driver(integ, tick_ns, substeps);
    State x = start_;
    out.resize(static_cast<std::size_t>(captured_));
    for (std::int64_t i = 0; i < captured_; ++i) {
      apply(m, inputs_[static_cast<std::size_t>(i)]);
      driver.advance_tick(first_ + i, x);
      out[static_cast<std::size_t>(i)] = x;
    }
  }

  std::int64_t first_, size_;
  std::int64_t captured_{0};
  State start_{State::Zero()};
  std::vector<Inputs> inputs_;
  std::vector<State> states_;
};

}  // namespace gyrostab::analysis
