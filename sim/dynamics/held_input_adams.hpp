// Fourth-order Adams-Bashforth across tick-held inputs: one right-hand side per step, for plants whose
// controller inputs enter affinely, x' = g(t, x) + G(x) u, with u held over each controller tick.
//
// Why: a one-step method must restart at every tick (u jumps there), and order 4 then costs four
// right-hand sides per step. A multistep method keeps its history across ticks, but the history of f as the
// plant saw it carries the old inputs: extrapolated into the new tick it errs by O(h·|G Δu|) per step
// (measured on the active ship: 3.3e-5 rad in roll, tools/derive/held_input_multistep.py). Here the history
// holds g(t_j, x_j) and x_j, and each step rebuilds F_j = g_j + G(x_j) u_k with the input u_k of the step
// being taken, so the extrapolated field is the one that acts now:
//   x_{k+1} = x_k + h/24 (55 F_0 − 59 F_1 + 37 F_2 − 9 F_3),   F_j = g(t_{k−j}, x_{k−j}) + G(x_{k−j}) u_k.
// What is left is the trajectory's kink at every input jump (x' jumps by G Δu, so g along it has a kinked
// derivative), a second-order error: in the active ship's accuracy study 1.5e-8 rad of roll at one step per
// tick, against RK4's 6e-15 (docs/accuracy.md). It is the cheapest method where that error is enough, not
// where round-off accuracy is asked for.
//
// Start-up and restarts: the first three steps, and any step whose state or step size is not the one the
// previous step produced (a reset, a re-simulation from a saved state), are RK4 steps (their first stage is
// the g_0 + G(x_0) u of the history, so a start-up step costs three more evaluations). Stability on a mode
// λ is AB4's: the half disk |hλ| ≤ 0.2, Re hλ ≤ 0 lies inside its region (its real interval is (−0.3, 0));
// plants with a mode faster than that (end-stop contact, nutation) belong to another method.
// Inputs count: a held viscous brake is a mode too (the ship's safe-state brake, 667 1/s, is hλ = 0.67 at
// 1 ms, outside the region), which is why this is the accuracy study's method and not a scene integrator.
//
// A Model provides, besides derivative() and project():
//   void derivative_without_inputs(double t, const State& x, State& g) const;   g(t, x): the held inputs off
//   void add_held_inputs(const State& x, State& dx) const;                       dx += G(x) u (u as held now)
// with G(x) u affine in x (additive torques, viscous brakes), so that the four input terms of a step are one
// evaluation at the history's weighted mean state.
// State: the model's. Allocation-free: the history is four states and four derivatives.
// Docs: docs/models/integrators.md#methods
#pragma once

namespace gyrostab::dynamics {

template <class Model>
concept HeldInputModel = requires(const Model& m, double t, const typename Model::State& x,
                                  typename Model::State& dx) {
  m.derivative_without_inputs(t, x, dx);
  m.add_held_inputs(x, dx);
};

template <class Model>
class HeldInputAdams4 {
 public:
  using State = typename Model::State;
  static constexpr const char* kName = "held-input-adams4";

  explicit HeldInputAdams4(const Model& model) : model_(model) {
    for (int j = 0; j < 4; ++j) {  // never read before written; zeroed so no compiler has to prove it
      g_[j].setZero();
      x_[j].setZero();
    }
  }

  void step(double t, double h, State& x) {
    if (!(filled_ > 0 && h == h_ && x == x_next_)) filled_ = 0;  // not the continuation: start again
    head_ = (head_ + 3) & 3;                                     // slot of the newest entry
    model_.derivative_without_inputs(t, x, g_[head_]);
    x_[head_] = x;
    if (filled_ < 4) ++filled_;
    if (filled_ < 4) {
      rk4_from_history(t, h, x);
    } else {
      // G(x) u is affine in x, so Σ b_j G(x_j) u = 24 G(x̄) u with x̄ = Σ b_j x_j / 24: one input evaluation.
      const int s0 = head_, s1 = (head_ + 1) & 3, s2 = (head_ + 2) & 3, s3 = (head_ + 3) & 3;
      State acc = kB[0] * g_[s0] + kB[1] * g_[s1] + kB[2] * g_[s2] + kB[3] * g_[s3];
      const State xbar = (kB[0] * x_[s0] + kB[1] * x_[s1] + kB[2] * x_[s2] + kB[3] * x_[s3]) * kInv24;
      State input = State::Zero();
      model_.add_held_inputs(xbar, input);
      x += (h * kInv24) * acc + h * input;
    }
    model_.project(x);
    h_ = h;
    x_next_ = x;
  }

  // Steps taken since the last (re)start, at most 4 (tests).
  int history() const { return filled_; }

 private:
  static constexpr double kB[4] = {55.0, -59.0, 37.0, -9.0};
  static constexpr double kInv24 = 1.0 / 24.0;

  void rk4_from_history(double t, double h, State& x) {
    State k1 = g_[head_];
    model_.add_held_inputs(x, k1);
    State k2, k3, k4;
    model_.derivative(t + 0.5 * h, x + (0.5 * h) * k1, k2);
    model_.derivative(t + 0.5 * h, x + (0.5 * h) * k2, k3);
    model_.derivative(t + h, x + h * k3, k4);
    x += (h / 6.0) * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
  }

  const Model& model_;
  State g_[4], x_[4];
  State x_next_{State::Zero()};
  double h_{0.0};
  int head_{0};
  int filled_{0};
};

}  // namespace gyrostab::dynamics
