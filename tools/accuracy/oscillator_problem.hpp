// A study problem with an analytic oracle: the undamped oscillator x'' = −ω² x + u_k, the force u_k held
// over tick k (zero-order hold, as every scene input is). The study's oracle path and its peers are held to
// closed forms with it (tests/study/): over a tick with u constant the exact flow is
//   x(t_k + τ) = u/ω² + (x_k − u/ω²) cos ωτ + (v_k/ω) sin ωτ,   v(t_k + τ) = −ω (x_k − u/ω²) sin ωτ + v_k cos ωτ.
// State x = [x, v]. Quantities: position (max over ticks of |Δx|) and energy (max over ticks of
// |ΔE|/E(0), E = ½ v² + ½ ω² x², E of the run against E of the oracle at the same tick).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "tools/accuracy/study_problem.hpp"

namespace gyrostab::tools::accuracy {

struct OscillatorModel {
  static constexpr int kStateSize = 2;
  using State = Eigen::Matrix<double, 2, 1>;
  double omega2{1.0};  // ω² [1/s²]
  double u{0.0};       // force per unit mass held over the tick [m/s²]

  void derivative(double /*t*/, const State& x, State& dx) const {
    dx[0] = x[1];
    dx[1] = -omega2 * x[0] + u;
  }
  void project(State&) const {}
};

class OscillatorProblem {
 public:
  using Model = OscillatorModel;
  static constexpr int kStateSize = 2;
  using State = Model::State;
  static constexpr int kQuantities = 2;

  // `force[k]` is held over tick k; the window is force.size() ticks.
  OscillatorProblem(double omega, std::int64_t tick_ns, std::vector<double> force, State x0)
      : omega_(omega), tick_ns_(tick_ns), force_(std::move(force)), x0_(x0) {
    model_.omega2 = omega * omega;
  }

  Model& model() { return model_; }
  void set_tick(std::int64_t k) { model_.u = force_[static_cast<std::size_t>(k)]; }
  State initial_state() const { return x0_; }
  std::int64_t ticks() const { return static_cast<std::int64_t>(force_.size()); }
  std::int64_t tick_ns() const { return tick_ns_; }

  std::array<Quantity, kQuantities> quantities() const {
    return {{{"position", "m", "max over ticks of |dx|"},
             {"energy_drift", "-", "max over ticks of |E - E_oracle| / E(0), E = v^2/2 + w^2 x^2/2"}}};
  }

  void errors(const Trajectory<State>& run, const Trajectory<State>& ref, double* out) const {
    const double e0 = energy(ref[0]);
    double position = 0.0, drift = 0.0;
    for (std::size_t k = 0; k < run.size(); ++k) {
      if (!run[k].allFinite()) {
        out[0] = out[1] = INFINITY;
        return;
      }
      position = std::max(position, std::abs(run[k][0] - ref[k][0]));
      drift = std::max(drift, std::abs(energy(run[k]) - energy(ref[k])) / e0);
    }
    out[0] = position;
    out[1] = drift;
  }

  void scales(const Trajectory<State>& ref, double* out) const {
    out[0] = 0.0;
    for (const State& x : ref) out[0] = std::max(out[0], std::abs(x[0]));
    out[1] = 1.0;  // already relative
  }

  // The oracle: the exact flow tick by tick (one rounding per tick).
  void exact(Trajectory<State>& out) const {
    const double tau = 1e-9 * static_cast<double>(tick_ns_);
    const double c = std::cos(omega_ * tau), s = std::sin(omega_ * tau);
    State x = x0_;
    out[0] = x;
    for (std::size_t k = 0; k < force_.size(); ++k) {
      const double rest = force_[k] / (omega_ * omega_);
      const double d = x[0] - rest;
      x = State(rest + d * c + x[1] / omega_ * s, -omega_ * d * s + x[1] * c);
      out[k + 1] = x;
    }
  }

  double energy(const State& x) const { return 0.5 * x[1] * x[1] + 0.5 * omega_ * omega_ * x[0] * x[0]; }

 private:
  double omega_;
  std::int64_t tick_ns_;
  std::vector<double> force_;
  State x0_;
  Model model_{};
};

}  // namespace gyrostab::tools::accuracy
