// Exponential integrator for gimbal gyros: the fast gyroscopic (nutation) coupling and the viscous bearing
// damping are integrated exactly; everything else is carried through that flow as a forcing held over the
// step.
//
// Models in generalised coordinates (Magnus (10.4), (11.1)) have the form
//   q' = v,   v' = K(x) v + r(t, x),   K = [[-p, -a], [b, -q]],
//   a = H cosβ/I(β),  b = H cosβ/B,  p = d1/I(β),  q = d2/B,
// where K carries the nutation ω_N = sqrt(ab) and its viscous decay (A d2 + B d1)/(2AB), and r (gravity,
// motors, Coulomb friction, the Q sin2β α'β' terms, base motion) is slow or small. With K and r frozen the
// flow is closed-form (damped_gyroscopic_flow.hpp: one complex exponential).
// Step (exponential midpoint): freeze K, r at (t, x) and flow h/2 to a midpoint; freeze K, r there and
// flow the whole step from x. Second order; exact for the linear damped nutation at any hω_N (no numerical
// damping, no frequency error) and for constant torque (so the precession rate M/H has no step error —
// unlike velocity-space Strang kicks, which scale it by (hω/2)/sin(hω/2), +7 % at hω = 1.26).
// What it does not resolve: forcing that itself oscillates at the nutation frequency (e.g. a gravity
// stiffness Gs α/A riding on the nutation) is midpoint-sampled, a relative error ~(hω_N)²/24 in that
// term's contribution — 4e-6 of ω_N for the 200 Hz pendulous stabilizer at 1 kHz.
// Remaining states (e.g. H) take the midpoint derivative.
//
// A Model provides the State layout [q0, q1, v0, v1, ...], derivative(), project() and
// gyroscopic_pair(x) -> GyroscopicPair; optionally derivative_with_pair(t, x, dx) -> GyroscopicPair, both from
// one evaluation of the model's trigonometry (the same numbers; about a third less work per step for a
// gimbal gyro, whose sinβ, cosβ and I(β) both need).
// Docs: docs/models/integrators.md#methods
#pragma once

#include <concepts>

#include "sim/dynamics/damped_gyroscopic_flow.hpp"
#include "sim/dynamics/step_start.hpp"

namespace gyrostab::dynamics {

template <class Model>
class GyroscopicExponential {
 public:
  using State = typename Model::State;
  static constexpr int N = Model::kStateSize;
  static constexpr const char* kName = "gyro-exponential";

  explicit GyroscopicExponential(const Model& model) : model_(model) {}

  void step(double t, double h, State& x) {
    begin_step(model_, t, h, x);
    flow(x, stage(t, x), x, 0.5 * h, mid_);
    flow(mid_, stage(t + 0.5 * h, mid_), x, h, next_);
    x = next_;
    model_.project(x);
  }

 private:
  static constexpr bool kSharedTrig = requires(const Model& m, double t, const State& x, State& dx) {
    { m.derivative_with_pair(t, x, dx) } -> std::convertible_to<GyroscopicPair>;
  };
  // f_ and K at (t, at).
  GyroscopicPair stage(double t, const State& at) {
    if constexpr (kSharedTrig) {
      return model_.derivative_with_pair(t, at, f_);
    } else {
      model_.derivative(t, at, f_);
      return model_.gyroscopic_pair(at);
    }
  }
  // Freeze K (k) and r at `at` (where f_ was evaluated) and flow `from` over tau into `out`.
  void flow(const State& at, const GyroscopicPair& k, const State& from, double tau, State& out) const {
    const double r0 = f_[2] + k.p * at[2] + k.a * at[3];
    const double r1 = f_[3] - k.b * at[2] + k.q * at[3];
    damped_gyroscopic_flow(k, tau, r0, r1, from.data(), out.data());
    for (int i = 4; i < N; ++i) out[i] = from[i] + tau * f_[i];
  }

  const Model& model_;
  State f_, mid_, next_;
};

}  // namespace gyrostab::dynamics
