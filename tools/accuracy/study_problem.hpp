// What the accuracy study integrates: a scene's plant as an ODE on the controller's tick grid, open loop,
// with every input held (zero-order hold) over a tick exactly as the scene's closed-loop run held it, and
// continuous disturbances (sea moment, base motion) as functions of t inside the right-hand side. The same
// right-hand side and the same error measure serve every method, ours and the peers' (docs/accuracy.md).
//
// A Problem provides
//   static constexpr int kStateSize;  using State = Eigen::Matrix<double, kStateSize, 1>;
//   using Model = ...;                   the plant as integrated: derivative(t, x, dx), project(x) and,
//                                        where it has one, gyroscopic_pair(x) (sim/dynamics integrators)
//   static constexpr int kQuantities;
//   Model& model();                      set_tick(k) writes tick k's held inputs into it
//   void set_tick(std::int64_t k);
//   State initial_state() const;
//   std::int64_t ticks() const, tick_ns() const;
//   std::array<Quantity, kQuantities> quantities() const;   quantity 0 is the primary one (speed-up, rank)
//   void errors(const Trajectory<State>& run, const Trajectory<State>& ref, double* out) const;
//   void scales(const Trajectory<State>& ref, double* out) const;   per quantity, the largest magnitude of
//                                        the signal it measures (the reference's round-off level, ReferenceInfo)
// and optionally an analytic oracle:
//   void exact(Trajectory<State>& out) const;   the exact state at every tick boundary
// A Trajectory holds the state at every tick boundary, ticks() + 1 entries, entry 0 the initial state.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <vector>

namespace gyrostab::tools::accuracy {

template <class State>
using Trajectory = std::vector<State>;  // C++17 aligned new: fixed-size Eigen members need no allocator

struct Quantity {
  const char* name;        // CSV/JSON key, e.g. "attitude_rad"
  const char* unit;        // e.g. "rad"
  const char* definition;  // how the error is computed, for the report and docs
};

template <class P>
concept HasOracle = requires(const P& p, Trajectory<typename P::State>& out) { p.exact(out); };

// Tick k starts at t = k·tick_ns·1e-9 s, computed from the integer tick as dynamics::SubstepDriver does.
inline double tick_time(std::int64_t k, std::int64_t tick_ns) { return 1e-9 * static_cast<double>(k * tick_ns); }

// The plant with a right-hand-side counter, seen by every method alike: an increment per evaluation (well
// under 1 % of any plant's evaluation). Forwards what the sim/dynamics integrators use.
template <class M>
struct CountedModel {
  static constexpr int kStateSize = M::kStateSize;
  using State = typename M::State;

  const M* model;
  mutable std::int64_t evaluations{0};

  void derivative(double t, const State& x, State& dx) const {
    ++evaluations;
    model->derivative(t, x, dx);
  }
  void project(State& x) const { model->project(x); }
  void derivative_without_inputs(double t, const State& x, State& g) const
    requires requires(const M& m, State& dx) { m.derivative_without_inputs(t, x, dx); }
  {
    ++evaluations;
    model->derivative_without_inputs(t, x, g);
  }
  void add_held_inputs(const State& x, State& dx) const
    requires requires(const M& m, State& d) { m.add_held_inputs(x, d); }
  {
    model->add_held_inputs(x, dx);
  }
  auto gyroscopic_pair(const State& x) const
    requires requires(const M& m) { m.gyroscopic_pair(x); }
  {
    return model->gyroscopic_pair(x);
  }
  auto derivative_with_pair(double t, const State& x, State& dx) const
    requires requires(const M& m) { m.derivative_with_pair(t, x, dx); }
  {
    ++evaluations;
    return model->derivative_with_pair(t, x, dx);
  }
};

}  // namespace gyrostab::tools::accuracy
